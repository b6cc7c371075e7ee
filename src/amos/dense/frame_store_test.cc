#include "amos/dense/frame_store.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/core/error.h"

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

TEST(FrameStore, ADamagedKeptFrameIsAnErrorNotAWrongImage) {
  PreparedFrame f{cv::Mat(60, 80, CV_32F, cv::Scalar(2.0f)), cv::Mat::zeros(60, 80, CV_32F),
                  cv::Mat(60, 80, CV_8UC3, cv::Scalar(1, 2, 3))};
  StoredFrame stored = compressFrame(f, 1.0, core::SE3::Identity());
  stored.depth_mm_zlib[stored.depth_mm_zlib.size() / 2] ^= 0x5a;
  try {
    decompressDepth(stored);
    FAIL() << "a damaged depth stream decoded";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("kept frame's depth does not decode"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace amos::dense
