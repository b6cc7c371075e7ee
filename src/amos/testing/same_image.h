#pragma once
// For tests: two images with the same type, size and pixels (or both empty), with what differs when they are not;
// the second is OpenCV's result that the first is compared with.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace amos::testing {

inline ::testing::AssertionResult sameImage(const cv::Mat& ours, const cv::Mat& opencv) {
  if (ours.empty() || opencv.empty()) {
    if (ours.empty() && opencv.empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << (ours.empty() ? "ours is empty, OpenCV's is not"
                                                          : "OpenCV's is empty, ours is not");
  }
  if (ours.type() != opencv.type() || ours.size() != opencv.size())
    return ::testing::AssertionFailure() << "ours is " << ours.cols << "x" << ours.rows << " "
                                         << cv::typeToString(ours.type()) << ", OpenCV's " << opencv.cols << "x"
                                         << opencv.rows << " " << cv::typeToString(opencv.type());
  const double diff = cv::norm(ours, opencv, cv::NORM_INF);
  if (diff != 0) return ::testing::AssertionFailure() << "pixels differ by up to " << diff;
  return ::testing::AssertionSuccess();
}

}  // namespace amos::testing
