#include "amos/core/binary_stream.h"

#include <gtest/gtest.h>

namespace amos::core {
namespace {

TEST(Crc32, KnownValues) {
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);  // the check value of CRC-32/ISO-HDLC
  EXPECT_EQ(crc32(""), 0u);
  EXPECT_NE(crc32("123456788"), crc32("123456789"));
}

TEST(ByteStream, ValuesComeBackInOrderAndReadingPastTheEndNamesTheSource) {
  ByteWriter w;
  w.put<std::uint32_t>(7);
  w.put(2.5);
  w.put<std::uint64_t>(1);  // a count of one 4-byte item ...
  w.put<std::int32_t>(-3);  // ... which is there
  ByteReader r(w.bytes(), "test.bin");
  EXPECT_EQ(r.get<std::uint32_t>("a"), 7u);
  EXPECT_EQ(r.get<double>("b"), 2.5);
  EXPECT_EQ(r.getCount(4, "items"), 1u);
  EXPECT_EQ(r.get<std::int32_t>("item"), -3);
  EXPECT_EQ(r.remaining(), 0u);
  try {
    r.get<std::uint8_t>("flag");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.bin: malformed: flag"), std::string::npos) << e.what();
  }
  ByteWriter huge;
  huge.put<std::uint64_t>(1000000000);
  ByteReader h(huge.bytes(), "huge.bin");
  EXPECT_THROW(h.getCount(32, "descriptors"), Error);  // a corrupt count cannot make the caller allocate
}

}  // namespace
}  // namespace amos::core
