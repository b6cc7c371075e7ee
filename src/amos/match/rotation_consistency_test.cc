#include "amos/match/rotation_consistency.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"

namespace amos::match {
namespace {

TEST(RotationHistogram, BinsAreCentredOnMultiplesOfTheBinWidth) {
  const RotationHistogram h;  // 30 bins of 12 degrees
  EXPECT_EQ(h.binOf(100, 100), 0);
  EXPECT_EQ(h.binOf(105.9f, 100), 0);
  EXPECT_EQ(h.binOf(94.1f, 100), 0);  // -5.9 wraps to 354.1, which rounds to bin 30 = bin 0
  EXPECT_EQ(h.binOf(1, 359), 0);      // +2 across the wrap
  EXPECT_EQ(h.binOf(359, 1), 0);      // -2 across the wrap
  EXPECT_EQ(h.binOf(130, 100), 3);    // +30 -> 2.5 bins, rounds half away from zero
  EXPECT_EQ(h.binOf(124, 100), 2);
  EXPECT_EQ(h.binOf(100, 124), 28);               // -24 = 336 degrees
  EXPECT_EQ(h.binOf(-700, 20), h.binOf(20, 20));  // any input range: -720 is a full turn twice
  EXPECT_THROW(RotationHistogram(0), core::Error);
}

TEST(RotationHistogram, KeepsTheThreeMostPopulatedBins) {
  RotationHistogram h;
  int id = 0;
  // 20 votes in bin 5 (60 deg), 8 in bin 6 (72), 3 in bin 4 (48), 2 in bin 20, 1 in bin 10.
  for (int i = 0; i < 20; ++i) h.add(id++, 160, 100);
  for (int i = 0; i < 8; ++i) h.add(id++, 172, 100);
  for (int i = 0; i < 3; ++i) h.add(id++, 148, 100);
  for (int i = 0; i < 2; ++i) h.add(id++, 340, 100);
  h.add(id++, 220, 100);
  const std::vector<int> kept = h.consistent();
  ASSERT_EQ(kept.size(), 31u);
  for (int i = 0; i < 31; ++i) EXPECT_EQ(kept[static_cast<size_t>(i)], i);
  EXPECT_EQ(h.inconsistent(), (std::vector<int>{31, 32, 33}));
}

TEST(RotationHistogram, MinorBinsBelowTenPercentAreDropped) {
  RotationHistogram h;
  for (int i = 0; i < 50; ++i) h.add(i, 10, 10);   // bin 0
  for (int i = 50; i < 54; ++i) h.add(i, 40, 10);  // bin 3 (30 deg -> 2.5 -> 3): 4 < 5 = 10% of 50
  h.add(54, 100, 10);                              // bin 8 (90 deg -> 7.5 -> 8): 1 vote
  EXPECT_EQ(h.consistent().size(), 50u);
  EXPECT_EQ(h.inconsistent(), (std::vector<int>{50, 51, 52, 53, 54}));
}

TEST(RotationHistogram, EmptyAndTies) {
  EXPECT_TRUE(RotationHistogram().consistent().empty());
  RotationHistogram h;
  // Four bins with one vote each: the three lowest bins win the tie.
  h.add(7, 0, 0);    // bin 0
  h.add(8, 0, 24);   // -24 -> bin 28
  h.add(9, 24, 0);   // bin 2
  h.add(10, 48, 0);  // bin 4
  EXPECT_EQ(h.consistent(), (std::vector<int>{7, 9, 10}));
  EXPECT_EQ(h.inconsistent(), std::vector<int>{8});
}

}  // namespace
}  // namespace amos::match
