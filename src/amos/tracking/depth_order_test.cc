#include "amos/tracking/depth_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace amos::tracking {
namespace {

// What the callers take from the order: closest first, every point within close_depth, then more until they have
// more than min_count (the loop of addTemporaryPoints and insertKeyFrame).
std::vector<int> taken(const std::vector<std::pair<float, int>>& by_depth, double close_depth, int min_count) {
  std::vector<int> out;
  int n = 0;
  for (const auto& [z, i] : by_depth) {
    out.push_back(i);
    ++n;
    if (z > close_depth && n > min_count) break;
  }
  return out;
}

map::FrameFeatures randomDepths(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cm(-50, 600);  // a few without depth, many equal depths
  map::FrameFeatures f;
  f.keys.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) f.depth.push_back(static_cast<float>(cm(rng)) / 100.f);
  return f;
}

TEST(KeypointsByDepth, TakesTheSamePointsAsAFullSort) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const map::FrameFeatures f = randomDepths(400, seed);
    std::vector<std::pair<float, int>> all;
    for (std::size_t i = 0; i < f.size(); ++i)
      if (f.depth[i] > 0) all.emplace_back(f.depth[i], static_cast<int>(i));
    std::sort(all.begin(), all.end());
    for (const double close : {0.0, 0.5, 2.0, 3.1, 10.0}) {
      for (const int min_count : {0, 1, 50, 100, 399, 1000}) {
        const auto partial = keypointsByDepth(f, close, min_count);
        EXPECT_EQ(taken(partial, close, min_count), taken(all, close, min_count))
            << "seed " << seed << " close " << close << " min " << min_count;
        ASSERT_TRUE(std::is_sorted(partial.begin(), partial.end()));
      }
    }
  }
}

TEST(KeypointsByDepth, KeepsOnlyThePrefixTheCallersRead) {
  map::FrameFeatures f;
  f.keys.resize(6);
  f.depth = {3.f, 0.f, 1.f, 5.f, 2.f, 4.f};
  const auto by_depth = keypointsByDepth(f, 2.5, 1);  // 1 and 2 m close, then one more: 3 m
  ASSERT_EQ(by_depth.size(), 3u);
  EXPECT_EQ(by_depth[0].second, 2);
  EXPECT_EQ(by_depth[1].second, 4);
  EXPECT_EQ(by_depth[2].second, 0);
}

}  // namespace
}  // namespace amos::tracking
