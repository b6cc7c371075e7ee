#include "amos/eval/associate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace amos::eval {
namespace {

using Pairs = std::vector<std::pair<std::size_t, std::size_t>>;

TEST(Associate, NearestWithinRadiusEachStampOnce) {
  const std::vector<double> a{1.00, 2.00, 3.00};
  const std::vector<double> b{1.005, 1.010, 2.019, 3.5};
  // 1.00 takes 1.005 (the closer), 1.010 stays unused; 2.00-2.019 is within 0.02; 3.5 is too far.
  EXPECT_EQ(associate(a, b), (Pairs{{0, 0}, {1, 2}}));
}

TEST(Associate, RadiusIsStrict) {
  // |a - b| == max_difference is not a match in associate.py (strict '<').
  EXPECT_TRUE(associate({1.0}, {1.5}, {0.5, 0.0}).empty());
  EXPECT_EQ(associate({1.0}, {1.4999}, {0.5, 0.0}), (Pairs{{0, 0}}));
}

TEST(Associate, GreedyBySmallestDifferenceNotBySequenceOrder) {
  // a0 would take b0 if processed first, but a1-b0 is the closest pair overall, so a0 gets nothing within 0.02.
  const std::vector<double> a{0.000, 0.012};
  const std::vector<double> b{0.011};
  EXPECT_EQ(associate(a, b), (Pairs{{1, 0}}));
}

TEST(Associate, TiesGoToTheSmallerStamp) {
  // b0 is equally far (0.005) from a0 and a1: the tuple sort (diff, a, b) gives it to the smaller a.
  const std::vector<double> a{0.0, 0.01};
  const std::vector<double> b{0.005};
  EXPECT_EQ(associate(a, b), (Pairs{{0, 0}}));
}

TEST(Associate, UnsortedInputsGiveIndicesIntoTheInputsSortedByFirstStamp) {
  const std::vector<double> a{3.0, 1.0, 2.0};
  const std::vector<double> b{2.001, 0.999, 3.002};
  EXPECT_EQ(associate(a, b), (Pairs{{1, 1}, {2, 0}, {0, 2}}));
}

TEST(Associate, OffsetIsAddedToTheSecondList) {
  const std::vector<double> a{10.0, 11.0};
  const std::vector<double> b{0.0, 1.0};
  EXPECT_TRUE(associate(a, b).empty());
  EXPECT_EQ(associate(a, b, {0.02, 10.0}), (Pairs{{0, 0}, {1, 1}}));
}

TEST(Associate, EmptyInputs) {
  EXPECT_TRUE(associate({}, {1.0}).empty());
  EXPECT_TRUE(associate({1.0}, {}).empty());
}

TEST(Associate, WindowedSearchMatchesBruteForce) {
  // Dense, jittered stamps where many candidates compete: compare with the literal O(n m) procedure.
  std::vector<double> a, b;
  for (int i = 0; i < 300; ++i) a.push_back(0.0333 * i + 0.004 * std::sin(i * 1.7));
  for (int i = 0; i < 500; ++i) b.push_back(0.0201 * i + 0.006 * std::cos(i * 0.9));
  struct C {
    double d;
    std::size_t i, j;
  };
  std::vector<C> candidates;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (std::abs(a[i] - b[j]) < 0.02) candidates.push_back({std::abs(a[i] - b[j]), i, j});
  std::sort(candidates.begin(), candidates.end(),
            [](const C& x, const C& y) { return std::tie(x.d, x.i, x.j) < std::tie(y.d, y.i, y.j); });
  std::vector<bool> ua(a.size()), ub(b.size());
  Pairs expected;
  for (const C& c : candidates) {
    if (ua[c.i] || ub[c.j]) continue;
    ua[c.i] = ub[c.j] = true;
    expected.emplace_back(c.i, c.j);
  }
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(associate(a, b), expected);
  EXPECT_GT(expected.size(), 250u);
}

TEST(SortedUniqueByTimestamp, SortsAndKeepsTheLastDuplicateLikeAPythonDict) {
  std::vector<io::StampedPose> poses(4);
  const double stamps[] = {2.0, 1.0, 2.0, 0.5};
  for (int i = 0; i < 4; ++i) {
    poses[i].timestamp = stamps[i];
    poses[i].T_wc.translation() = Eigen::Vector3d(i, 0, 0);
  }
  const auto unique = sortedUniqueByTimestamp(poses);
  ASSERT_EQ(unique.size(), 3u);
  EXPECT_EQ(timestampsOf(unique), (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_EQ(unique[2].T_wc.translation().x(), 2.0);  // the later of the two 2.0 lines
}

}  // namespace
}  // namespace amos::eval
