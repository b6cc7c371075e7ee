#include "amos/viewer/file_reply.h"

#include <gtest/gtest.h>

namespace amos::viewer {
namespace {

using Kind = ByteSpan::Kind;

TEST(FileReply, ByteSpanOfOneRange) {
  EXPECT_EQ(byteSpanOf("", 100).kind, Kind::Whole);
  ByteSpan s = byteSpanOf("bytes=10-19", 100);
  EXPECT_EQ(s.kind, Kind::Part);
  EXPECT_EQ(s.offset, 10u);
  EXPECT_EQ(s.length, 10u);
  s = byteSpanOf("bytes=90-", 100);
  EXPECT_EQ(s.offset, 90u);
  EXPECT_EQ(s.length, 10u);
  s = byteSpanOf("bytes=-5", 100);
  EXPECT_EQ(s.offset, 95u);
  EXPECT_EQ(s.length, 5u);
  s = byteSpanOf("bytes=-500", 100);
  EXPECT_EQ(s.offset, 0u);
  EXPECT_EQ(s.length, 100u);
  s = byteSpanOf("bytes=50-99999999999", 100);  // its end clipped to the file's
  EXPECT_EQ(s.length, 50u);
  EXPECT_EQ(byteSpanOf("bytes=100-", 100).kind, Kind::Unsatisfiable);
  EXPECT_EQ(byteSpanOf("bytes=-0", 100).kind, Kind::Unsatisfiable);
  EXPECT_EQ(byteSpanOf("bytes=0-", 0).kind, Kind::Unsatisfiable);
  EXPECT_EQ(byteSpanOf("bytes=20-10", 100).kind, Kind::Whole);  // invalid: ignored
  EXPECT_EQ(byteSpanOf("items=0-1", 100).kind, Kind::Whole);
  EXPECT_EQ(byteSpanOf("bytes=0-1,5-6", 100).kind, Kind::Whole);
}

}  // namespace
}  // namespace amos::viewer
