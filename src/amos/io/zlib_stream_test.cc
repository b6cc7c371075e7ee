#include "amos/io/zlib_stream.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <vector>

#include "amos/core/error.h"

namespace amos::io {
namespace {

std::vector<std::uint16_t> depthRamp() {
  std::vector<std::uint16_t> samples(320 * 240);
  for (std::size_t i = 0; i < samples.size(); ++i) samples[i] = static_cast<std::uint16_t>(800 + (i % 320) * 7 + i / 320);
  return samples;
}

TEST(ZlibStream, RoundTripsBytesExactlyAndCompresses) {
  const std::vector<std::uint16_t> samples = depthRamp();
  const std::size_t bytes = samples.size() * sizeof(std::uint16_t);
  const std::vector<std::uint8_t> stream = deflateBytes(samples.data(), bytes, 1);
  EXPECT_LT(stream.size(), bytes / 2);
  std::vector<std::uint16_t> back(samples.size());
  inflateBytes(stream, back.data(), bytes);
  EXPECT_EQ(back, samples);
}

// The format is zlib's whichever library wrote it: zlib itself reads it back.
TEST(ZlibStream, WritesAStreamZlibReads) {
  const std::vector<std::uint16_t> samples = depthRamp();
  const std::size_t bytes = samples.size() * sizeof(std::uint16_t);
  const std::vector<std::uint8_t> stream = deflateBytes(samples.data(), bytes, 6);
  std::vector<std::uint16_t> back(samples.size());
  uLongf written = bytes;
  ASSERT_EQ(uncompress(reinterpret_cast<Bytef*>(back.data()), &written, stream.data(), stream.size()), Z_OK);
  EXPECT_EQ(written, bytes);
  EXPECT_EQ(back, samples);
}

TEST(ZlibStream, ACorruptOrWronglySizedStreamIsAnError) {
  const std::vector<std::uint16_t> samples = depthRamp();
  const std::size_t bytes = samples.size() * sizeof(std::uint16_t);
  std::vector<std::uint8_t> stream = deflateBytes(samples.data(), bytes, 1);
  std::vector<std::uint16_t> back(samples.size() + 1);
  EXPECT_THROW(inflateBytes(stream, back.data(), bytes + 2), core::Error);  // holds fewer bytes than asked
  EXPECT_THROW(inflateBytes(stream, back.data(), bytes - 2), core::Error);  // holds more
  stream[stream.size() / 2] ^= 0xff;
  EXPECT_THROW(inflateBytes(stream, back.data(), bytes), core::Error);
  EXPECT_THROW(inflateBytes({}, back.data(), bytes), core::Error);
}

}  // namespace
}  // namespace amos::io
