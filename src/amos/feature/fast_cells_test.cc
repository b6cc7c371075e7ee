#include "amos/feature/fast_cells.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <opencv2/features2d.hpp>

#include <random>
#include <set>

namespace amos::feature {
namespace {

// Smooth random texture (cubic upsampling of noise), strong on the left half (FAST scores far above 20) and faint
// on the right (amplitude chosen so that scores fall between 7 and 20: only the fallback threshold finds them).
cv::Mat twoContrastImage() {
  std::mt19937 rng(2);
  cv::Mat noise(60, 80, CV_32F);
  for (int y = 0; y < noise.rows; ++y)
    for (int x = 0; x < noise.cols; ++x) noise.at<float>(y, x) = static_cast<float>(rng() % 1000) / 1000.0f - 0.5f;
  cv::Mat texture;
  cv::resize(noise, texture, cv::Size(320, 240), 0, 0, cv::INTER_CUBIC);
  cv::Mat img(240, 320, CV_8UC1);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x)
      img.at<std::uint8_t>(y, x) =
          cv::saturate_cast<std::uint8_t>(128 + (x < 160 ? 200 : 30) * texture.at<float>(y, x));
  return img;
}

cv::Mat pad(const cv::Mat& img, int border) {
  cv::Mat padded;
  cv::copyMakeBorder(img, padded, border, border, border, border, cv::BORDER_REFLECT_101);
  return padded;
}

TEST(FastCells, LowerThresholdOnlyWhereTheCellIsEmpty) {
  const cv::Mat img = twoContrastImage();
  const int border = 19;
  const cv::Mat padded = pad(img, border);
  const auto strict = detectFastInCells(padded, border, img.size(), {20, 20, 30});
  const auto fallback = detectFastInCells(padded, border, img.size(), {20, 7, 30});
  int strict_right = 0, fallback_right = 0, fallback_weak_left = 0;
  for (const auto& kp : strict) strict_right += kp.pt.x >= 165 ? 1 : 0;
  for (const auto& kp : fallback) {
    fallback_right += kp.pt.x >= 165 ? 1 : 0;
    if (kp.pt.x < 150 && kp.response < 20) ++fallback_weak_left;
  }
  EXPECT_LT(strict_right, 5);
  EXPECT_GT(fallback_right, 50);
  // Cells on the left have strong corners, so they are not searched again with the low threshold.
  EXPECT_EQ(fallback_weak_left, 0);
  for (const auto& kp : fallback) {
    EXPECT_GE(kp.response, 7);
    EXPECT_GE(kp.pt.x, 0);
    EXPECT_LT(kp.pt.x, img.cols);
    EXPECT_GE(kp.pt.y, 0);
    EXPECT_LT(kp.pt.y, img.rows);
  }
}

TEST(FastCells, CornersMatchPlainFastInsideTheImage) {
  // With no fallback, the result is cv::FAST on the image (away from the border, where padding adds context).
  const cv::Mat img = twoContrastImage();
  const auto ours = detectFastInCells(pad(img, 19), 19, img.size(), {20, 20, 30});
  std::vector<cv::KeyPoint> reference;
  cv::FAST(img, reference, 20, true);
  auto interior = [&](const cv::KeyPoint& kp) {
    return kp.pt.x >= 4 && kp.pt.y >= 4 && kp.pt.x < img.cols - 4 && kp.pt.y < img.rows - 4;
  };
  std::set<std::pair<float, float>> a, b;
  for (const auto& kp : ours)
    if (interior(kp)) a.insert({kp.pt.x, kp.pt.y});
  for (const auto& kp : reference)
    if (interior(kp)) b.insert({kp.pt.x, kp.pt.y});
  EXPECT_EQ(a, b);
  EXPECT_GT(a.size(), 100u);
}

TEST(FastCells, MaskRemovesCornersBeforeTheFallbackDecision) {
  const cv::Mat img = twoContrastImage();
  cv::Mat mask(img.size(), CV_8UC1, cv::Scalar(255));
  mask(cv::Rect(0, 0, 160, 240)).setTo(0);  // forbid the strong half
  const auto kps = detectFastInCells(pad(img, 19), 19, img.size(), {20, 7, 30}, mask);
  for (const auto& kp : kps) EXPECT_GE(kp.pt.x, 160);
  EXPECT_GT(kps.size(), 50u);
}

// Texture running into the image edge: with the reflected border, the mirror axis makes corners right at the edge
// (pinned to the image, not to the scene). None closer than edge_margin may come out; with margin 0 they do.
TEST(FastCells, NoCornersWithinTheEdgeMargin) {
  const cv::Mat img = twoContrastImage();
  const int border = 19;
  const cv::Mat padded = pad(img, border);
  auto nearEdge = [&](const std::vector<cv::KeyPoint>& corners, int margin) {
    int n = 0;
    for (const auto& kp : corners) {
      const int x = static_cast<int>(kp.pt.x), y = static_cast<int>(kp.pt.y);
      n += (x < margin || y < margin || x >= img.cols - margin || y >= img.rows - margin) ? 1 : 0;
    }
    return n;
  };
  FastCellOptions options{20, 7, 30};
  ASSERT_EQ(options.edge_margin, 4);
  EXPECT_EQ(nearEdge(detectFastInCells(padded, border, img.size(), options), options.edge_margin), 0);
  options.edge_margin = 0;
  EXPECT_GT(nearEdge(detectFastInCells(padded, border, img.size(), options), 4), 0);
}

}  // namespace
}  // namespace amos::feature
