#include "amos/segmentation/segment_depth_mask.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"

namespace amos::segmentation {
namespace {

TEST(SegmentDepthMask, KeepsThePixelsAtTheObjectsDepth) {
  cv::Mat depth(120, 160, CV_32F, cv::Scalar(4.f));       // wall at 4 m
  depth(cv::Rect(50, 30, 40, 60)).setTo(1.5f);             // object at 1.5 m
  depth(cv::Rect(60, 50, 3, 3)).setTo(0.f);                // a small depth hole inside the object
  const cv::Rect box(40, 20, 60, 80);                      // detector box, a bit larger than the object
  const cv::Mat mask = boxDepthMask(depth, box, 0.4f);
  ASSERT_EQ(mask.size(), box.size());
  EXPECT_EQ(cv::countNonZero(mask), 40 * 60);              // the object, hole closed, no wall
  EXPECT_EQ(mask.at<uchar>(10 + 5, 10 + 5), 255);
  EXPECT_EQ(mask.at<uchar>(2, 2), 0);
}

TEST(SegmentDepthMask, WholeBoxWithoutUsableDepth) {
  const cv::Rect box(10, 10, 20, 20);
  EXPECT_EQ(cv::countNonZero(boxDepthMask(cv::Mat(), box, 0.4f)), 400);
  EXPECT_EQ(cv::countNonZero(boxDepthMask(cv::Mat(60, 60, CV_32F, cv::Scalar(0.f)), box, 0.4f)), 400);
  EXPECT_THROW(boxDepthMask(cv::Mat(60, 60, CV_16U, cv::Scalar(0)), box, 0.4f), core::Error);
  EXPECT_THROW(boxDepthMask(cv::Mat(20, 20, CV_32F, cv::Scalar(1.f)), box, 0.4f), core::Error);
}

}  // namespace
}  // namespace amos::segmentation
