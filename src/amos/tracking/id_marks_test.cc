#include "amos/tracking/id_marks.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"

namespace amos::tracking {
namespace {

TEST(IdMarks, InsertsOnceAndForgetsOnClear) {
  IdMarks marks;
  EXPECT_FALSE(marks.contains(3));
  EXPECT_TRUE(marks.insert(3));
  EXPECT_FALSE(marks.insert(3));
  EXPECT_TRUE(marks.contains(3));
  EXPECT_FALSE(marks.contains(2));
  EXPECT_TRUE(marks.insert(1000));  // grows
  EXPECT_TRUE(marks.contains(1000));
  EXPECT_TRUE(marks.contains(3));
  marks.clear();
  EXPECT_FALSE(marks.contains(3));
  EXPECT_FALSE(marks.contains(1000));
  EXPECT_TRUE(marks.insert(3));
  EXPECT_FALSE(marks.contains(1000));
}

TEST(IdMarks, StaysCorrectOverManyClears) {
  IdMarks marks;
  for (int round = 0; round < 1000; ++round) {
    marks.clear();
    EXPECT_TRUE(marks.insert(static_cast<std::uint64_t>(round % 7)));
    EXPECT_FALSE(marks.contains(static_cast<std::uint64_t>((round + 1) % 7)));
  }
}

TEST(IdMarks, RejectsTheNoIdSentinel) {
  IdMarks marks;
  EXPECT_THROW(marks.insert(~std::uint64_t{0}), core::Error);
}

}  // namespace
}  // namespace amos::tracking
