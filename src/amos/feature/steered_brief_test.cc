#include "amos/feature/steered_brief.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <random>
#include <set>
#include <tuple>

#include "amos/core/error.h"

namespace amos::feature {
namespace {

TEST(GaussianBriefPattern, DeterministicDistinctAndInsideTheDisc) {
  const auto a = makeGaussianBriefPattern(5), b = makeGaussianBriefPattern(5), c = makeGaussianBriefPattern(6);
  ASSERT_EQ(a.size(), 256u);
  std::set<std::tuple<int, int, int, int>> seen;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::tie(a[i].x1, a[i].y1, a[i].x2, a[i].y2), std::tie(b[i].x1, b[i].y1, b[i].x2, b[i].y2));
    EXPECT_LE(a[i].x1 * a[i].x1 + a[i].y1 * a[i].y1, 225);
    EXPECT_LE(a[i].x2 * a[i].x2 + a[i].y2 * a[i].y2, 225);
    EXPECT_FALSE(a[i].x1 == a[i].x2 && a[i].y1 == a[i].y2);
    EXPECT_TRUE(seen.insert({a[i].x1, a[i].y1, a[i].x2, a[i].y2}).second);
  }
  int differ = 0;
  for (size_t i = 0; i < a.size(); ++i) differ += a[i].x1 != c[i].x1 || a[i].y1 != c[i].y1 ? 1 : 0;
  EXPECT_GT(differ, 200);  // another seed, another pattern
}

TEST(SteeredBrief, BitsFollowTheRotatedTests) {
  // A horizontal ramp: I(x) increases with x, so bit i is 1 exactly when the second point is further right
  // than the first after rotation.
  cv::Mat ramp(101, 101, CV_8UC1);
  for (int y = 0; y < ramp.rows; ++y)
    for (int x = 0; x < ramp.cols; ++x) ramp.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(2 * x + 20);
  const std::vector<BriefPair> pattern = makeGaussianBriefPattern(1);
  const SteeredBrief brief(pattern);
  std::uint8_t d0[32], d90[32];
  brief.compute(ramp, 50, 50, 0.0f, d0);
  brief.compute(ramp, 50, 50, 90.0f, d90);  // +90 deg: pattern x -> image y, pattern y -> image -x
  for (int i = 0; i < 256; ++i) {
    const auto& p = pattern[static_cast<size_t>(i)];
    EXPECT_EQ((d0[i / 8] >> (i % 8)) & 1, p.x1 < p.x2 ? 1 : 0) << i;
    EXPECT_EQ((d90[i / 8] >> (i % 8)) & 1, -p.y1 < -p.y2 ? 1 : 0) << i;
  }
  EXPECT_THROW(SteeredBrief(std::vector<BriefPair>(10)), core::Error);
  EXPECT_THROW(SteeredBrief(std::vector<BriefPair>(256, BriefPair{20, 0, 0, 0})), core::Error);
}

}  // namespace
}  // namespace amos::feature
