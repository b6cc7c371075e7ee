#include "amos/feature/keypoint_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "amos/core/error.h"

namespace amos::feature {
namespace {

std::vector<int> bruteForce(const std::vector<cv::KeyPoint>& kps, double u, double v, double r, int min_level,
                            int max_level) {
  std::vector<int> out;
  for (size_t i = 0; i < kps.size(); ++i) {
    if (min_level >= 0 && kps[i].octave < min_level) continue;
    if (max_level >= 0 && kps[i].octave > max_level) continue;
    if (std::abs(kps[i].pt.x - u) < r && std::abs(kps[i].pt.y - v) < r) out.push_back(static_cast<int>(i));
  }
  return out;
}

TEST(KeypointGrid, AgreesWithBruteForceInCellMajorOrder) {
  // Undistorted bounds of a lens with barrel distortion stick out of the 640x480 image; some keypoints lie
  // outside even those bounds.
  const cv::Rect2d bounds(-12.5, -9.0, 667.0, 501.0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> ux(-30.0f, 680.0f), uy(-30.0f, 510.0f);
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 2000; ++i) {
    cv::KeyPoint kp(ux(rng), uy(rng), 31.0f);
    kp.octave = static_cast<int>(rng() % 8);
    kps.push_back(kp);
  }
  const KeypointGrid grid(bounds, kps);
  EXPECT_EQ(grid.size(), kps.size());
  std::uniform_real_distribution<double> radius(0.5, 120.0);
  size_t total = 0;
  std::vector<int> reused;
  for (int q = 0; q < 500; ++q) {
    const double u = ux(rng), v = uy(rng), r = radius(rng);
    const int min_level = static_cast<int>(rng() % 10) - 2;  // -2..7, negatives mean no bound
    const int max_level = static_cast<int>(rng() % 10) - 2;
    const std::vector<int> got = grid.featuresInArea(u, v, r, min_level, max_level);
    grid.featuresInArea(u, v, r, min_level, max_level, reused);
    EXPECT_EQ(got, reused);
    // Cell-major order, ascending index within a cell: callers' ties (the first of equal distances) depend on it.
    std::vector<int> expected = bruteForce(kps, u, v, r, min_level, max_level);
    std::stable_sort(expected.begin(), expected.end(), [&](int a, int b) {
      const auto cell = [&](int i) { return grid.cellRow(kps[i].pt.y) * grid.cols() + grid.cellCol(kps[i].pt.x); };
      return cell(a) < cell(b);
    });
    ASSERT_EQ(got, expected) << "query " << u << "," << v << " r " << r << " levels " << min_level << ".." << max_level;
    total += got.size();
  }
  EXPECT_GT(total, 5000u);  // the queries did find things
}

TEST(KeypointGrid, KnownSmallCase) {
  std::vector<cv::KeyPoint> kps = {cv::KeyPoint(10, 10, 31), cv::KeyPoint(14, 10, 31), cv::KeyPoint(300, 200, 31)};
  kps[1].octave = 2;
  const KeypointGrid grid(cv::Rect2d(0, 0, 640, 480), kps);
  EXPECT_EQ(grid.cols(), 64);
  EXPECT_EQ(grid.rows(), 48);
  EXPECT_EQ(grid.cellCol(10), 1);
  EXPECT_EQ(grid.cellRow(479.9), 47);
  EXPECT_EQ(grid.cellCol(-5), 0);
  EXPECT_EQ(grid.cellCol(1e9), 63);
  auto sorted = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  EXPECT_EQ(sorted(grid.featuresInArea(12, 10, 3)), (std::vector<int>{0, 1}));
  EXPECT_EQ(grid.featuresInArea(12, 10, 2), std::vector<int>{});  // the window is open: |10 - 12| < 2 fails
  EXPECT_EQ(grid.featuresInArea(12, 10, 3, 1), std::vector<int>{1});
  EXPECT_EQ(grid.featuresInArea(12, 10, 3, -1, 1), std::vector<int>{0});
  EXPECT_EQ(grid.featuresInArea(300, 200, 0.5), std::vector<int>{2});
  EXPECT_TRUE(grid.featuresInArea(300, 200, 0).empty());
  EXPECT_TRUE(KeypointGrid().featuresInArea(1, 1, 10).empty());
  EXPECT_THROW(KeypointGrid(cv::Rect2d(0, 0, 0, 480), kps), core::Error);
}

}  // namespace
}  // namespace amos::feature
