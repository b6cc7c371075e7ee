#include "amos/dense/frame_store.h"

#include <gtest/gtest.h>

#include <cmath>

namespace amos::dense {
namespace {

TEST(FrameStore, KeepsDepthToAMillimetreAndColourClose) {
  PreparedFrame f{cv::Mat(60, 80, CV_32F), cv::Mat::zeros(60, 80, CV_32F), cv::Mat(60, 80, CV_8UC3)};
  cv::randu(f.depth, 0.3, 4.0);
  f.removed(cv::Rect(10, 10, 5, 5)).setTo(2.5f);
  f.bgr.setTo(cv::Scalar(10, 100, 200));
  const StoredFrame stored = compressFrame(f, 12.5, core::SE3::Identity());
  const PreparedFrame back = decompressFrame(stored);
  double worst = 0;
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 80; ++u) worst = std::max(worst, double(std::abs(back.depth.at<float>(v, u) - f.depth.at<float>(v, u))));
  EXPECT_LE(worst, 0.0005 + 1e-6);
  EXPECT_FLOAT_EQ(back.removed.at<float>(12, 12), 2.5f);
  EXPECT_EQ(back.removed.at<float>(0, 0), 0.0f);
  EXPECT_NEAR(back.bgr.at<cv::Vec3b>(30, 30)[2], 200, 3);
  EXPECT_EQ(stored.timestamp, 12.5);
}

}  // namespace
}  // namespace amos::dense
