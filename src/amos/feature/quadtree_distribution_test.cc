#include "amos/feature/quadtree_distribution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

namespace amos::feature {
namespace {

std::vector<cv::KeyPoint> randomKeypoints(int n, float w, float h, unsigned seed) {
  std::mt19937 rng(seed);
  std::set<std::pair<int, int>> used;
  std::vector<cv::KeyPoint> kps;
  while (static_cast<int>(kps.size()) < n) {
    const int x = static_cast<int>(rng() % static_cast<unsigned>(w)),
              y = static_cast<int>(rng() % static_cast<unsigned>(h));
    if (!used.insert({x, y}).second) continue;
    kps.emplace_back(static_cast<float>(x), static_cast<float>(y), 7.0f, -1.0f, static_cast<float>(rng() % 100));
  }
  return kps;
}

TEST(QuadtreeDistribution, ReachesTheTargetAndSpreadsEvenly) {
  // Dense clutter in the top-left corner plus a sparse sprinkle elsewhere: a plain "strongest N" would take
  // everything from the clutter; the quadtree must still cover the whole image.
  std::vector<cv::KeyPoint> kps = randomKeypoints(3000, 160, 120, 1);
  for (auto& kp : kps) kp.response += 1000;  // the clutter is also the strongest
  for (const auto& kp : randomKeypoints(400, 640, 480, 2)) kps.push_back(kp);
  const std::vector<int> kept = distributeQuadtree(kps, cv::Rect2f(0, 0, 640, 480), 200);
  EXPECT_EQ(kept.size(), 200u);
  EXPECT_EQ(std::set<int>(kept.begin(), kept.end()).size(), kept.size());  // no duplicates
  int in_clutter = 0;
  int cells[4][4] = {};
  for (int i : kept) {
    const cv::Point2f p = kps[static_cast<size_t>(i)].pt;
    in_clutter += p.x < 160 && p.y < 120 ? 1 : 0;
    cells[static_cast<int>(p.y) / 120][static_cast<int>(p.x) / 160]++;
  }
  EXPECT_LT(in_clutter, 60);  // far less than its 88% share of the candidates
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_GE(cells[r][c], 3) << r << "," << c;
  // Strongest first.
  for (size_t k = 1; k < kept.size(); ++k)
    EXPECT_GE(kps[static_cast<size_t>(kept[k - 1])].response, kps[static_cast<size_t>(kept[k])].response);
}

TEST(QuadtreeDistribution, KeepsTheStrongestOfEachCluster) {
  // Four tight clusters in the four quadrants; with a target of 4, one keypoint per cluster: its strongest.
  std::vector<cv::KeyPoint> kps;
  const cv::Point2f centres[4] = {{100, 100}, {500, 100}, {100, 400}, {500, 400}};
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 5; ++k)
      kps.emplace_back(centres[c].x + k, centres[c].y + k, 7.0f, -1.0f, static_cast<float>(10 * c + k));
  std::vector<int> kept = distributeQuadtree(kps, cv::Rect2f(0, 0, 640, 480), 4);
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(kept, (std::vector<int>{4, 9, 14, 19}));
}

TEST(QuadtreeDistribution, FewerCandidatesThanTargetKeepsAll) {
  const std::vector<cv::KeyPoint> kps = randomKeypoints(50, 640, 480, 3);
  std::vector<int> kept = distributeQuadtree(kps, cv::Rect2f(0, 0, 640, 480), 100);
  std::sort(kept.begin(), kept.end());
  ASSERT_EQ(kept.size(), 50u);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(kept[static_cast<size_t>(i)], i);
  EXPECT_TRUE(distributeQuadtree({}, cv::Rect2f(0, 0, 640, 480), 10).empty());
  EXPECT_TRUE(distributeQuadtree(kps, cv::Rect2f(0, 0, 640, 480), 0).empty());
}

TEST(QuadtreeDistribution, DuplicatePositionsTerminate) {
  // Many keypoints on the same pixel cannot be separated by splitting; the result is one of them.
  std::vector<cv::KeyPoint> kps(100, cv::KeyPoint(10.0f, 10.0f, 7.0f));
  for (size_t i = 0; i < kps.size(); ++i) kps[i].response = static_cast<float>(i % 7);
  const std::vector<int> kept = distributeQuadtree(kps, cv::Rect2f(0, 0, 640, 480), 50);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0], 6);  // strongest (response 6), lowest index among equals
}

}  // namespace
}  // namespace amos::feature
