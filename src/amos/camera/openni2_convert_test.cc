#include "amos/camera/openni2_convert.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "amos/core/error.h"

namespace amos::camera {
namespace {

// A 3 x 2 RGB888 buffer with 4 bytes of padding per row (as drivers may deliver).
TEST(OpenNI2Convert, Rgb888WithPaddedRowsBecomesBgr) {
  constexpr int kWidth = 3, kHeight = 2, kStride = kWidth * 3 + 4;
  std::vector<std::uint8_t> buffer(kStride * kHeight, 0xEE);  // padding must not leak into the image
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth; ++c) {
      std::uint8_t* px = &buffer[r * kStride + c * 3];
      px[0] = static_cast<std::uint8_t>(10 * r + c);  // R
      px[1] = 100;                                    // G
      px[2] = static_cast<std::uint8_t>(200 + c);     // B
    }
  }
  const cv::Mat bgr = rgb888ToBgr(buffer.data(), kWidth, kHeight, kStride);
  ASSERT_EQ(bgr.type(), CV_8UC3);
  ASSERT_EQ(bgr.size(), cv::Size(kWidth, kHeight));
  EXPECT_TRUE(bgr.isContinuous());
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth; ++c) {
      const cv::Vec3b px = bgr.at<cv::Vec3b>(r, c);
      EXPECT_EQ(px[0], 200 + c);
      EXPECT_EQ(px[1], 100);
      EXPECT_EQ(px[2], 10 * r + c);
    }
  }
  buffer[0] = 99;  // the output owns its pixels
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 0)[2], 0);
}

TEST(OpenNI2Convert, MillimetreDepthBecomesMetresAndZeroStaysZero) {
  constexpr int kWidth = 4, kHeight = 2, kStride = kWidth * 2 + 6;
  std::vector<std::uint8_t> buffer(kStride * kHeight, 0xFF);
  const std::uint16_t values[kHeight][kWidth] = {{0, 1, 1000, 65535}, {1234, 0, 500, 4000}};
  for (int r = 0; r < kHeight; ++r) std::memcpy(&buffer[r * kStride], values[r], sizeof(values[r]));
  const cv::Mat metres = depthToMetres(buffer.data(), kWidth, kHeight, kStride);
  ASSERT_EQ(metres.type(), CV_32F);
  ASSERT_EQ(metres.size(), cv::Size(kWidth, kHeight));
  for (int r = 0; r < kHeight; ++r) {
    for (int c = 0; c < kWidth; ++c) {
      EXPECT_FLOAT_EQ(metres.at<float>(r, c), static_cast<float>(values[r][c] * 0.001)) << r << "," << c;
    }
  }
  EXPECT_EQ(metres.at<float>(0, 0), 0.0f);
  EXPECT_EQ(metres.at<float>(1, 1), 0.0f);
  // 100 um units (PIXEL_FORMAT_DEPTH_100_UM)
  EXPECT_FLOAT_EQ(depthToMetres(buffer.data(), kWidth, kHeight, kStride, 1e-4).at<float>(0, 2), 0.1f);
}

TEST(OpenNI2Convert, BadBuffersAreClearErrors) {
  std::vector<std::uint8_t> buffer(64);
  EXPECT_THROW(rgb888ToBgr(nullptr, 2, 2, 6), core::Error);
  EXPECT_THROW(rgb888ToBgr(buffer.data(), 4, 2, 11), core::Error);  // stride shorter than a row
  EXPECT_THROW(depthToMetres(buffer.data(), 0, 2, 8), core::Error);
  EXPECT_THROW(depthToMetres(buffer.data(), 4, 2, 7), core::Error);
}

TEST(OpenNI2Convert, DeviceMicrosecondsAreSeconds) {
  EXPECT_EQ(deviceSeconds(0), 0.0);
  EXPECT_EQ(deviceSeconds(33333), 0.033333);
  EXPECT_EQ(deviceSeconds(123456789), 123.456789);
}

}  // namespace
}  // namespace amos::camera
