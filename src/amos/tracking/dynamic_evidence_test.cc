#include "amos/tracking/dynamic_evidence.h"

#include <gtest/gtest.h>

namespace amos::tracking {
namespace {

TEST(MaskEvidence, PointOnTheMoverCountsAsDynamic) {
  cv::Mat mask(10, 10, CV_8U, cv::Scalar(0));
  mask(cv::Rect(0, 0, 5, 10)).setTo(255);
  cv::Mat depth(10, 10, CV_32F, cv::Scalar(2.0f));
  EXPECT_EQ(maskEvidence(mask, depth, 2, 5, 2.02), MaskEvidence::kDynamic);
  EXPECT_EQ(maskEvidence(mask, depth, 7, 5, 2.02), MaskEvidence::kStatic);
}

TEST(MaskEvidence, PointHiddenBehindTheMoverSaysNothing) {
  cv::Mat mask(10, 10, CV_8U, cv::Scalar(255));
  cv::Mat depth(10, 10, CV_32F, cv::Scalar(1.5f));  // a person at 1.5 m in front of a wall point at 3 m
  EXPECT_EQ(maskEvidence(mask, depth, 4, 4, 3.0), MaskEvidence::kNone);
  EXPECT_EQ(maskEvidence(mask, depth, 4, 4, 1.55), MaskEvidence::kDynamic);  // within the noise band
}

TEST(MaskEvidence, MissingDepthOrMaskOrOutsideTheImage) {
  cv::Mat mask(10, 10, CV_8U, cv::Scalar(255));
  cv::Mat holes(10, 10, CV_32F, cv::Scalar(0.0f));
  EXPECT_EQ(maskEvidence(mask, holes, 4, 4, 3.0), MaskEvidence::kDynamic);  // no depth: trust the mask
  EXPECT_EQ(maskEvidence(mask, cv::Mat(), 4, 4, 3.0), MaskEvidence::kDynamic);
  EXPECT_EQ(maskEvidence(cv::Mat(), holes, 4, 4, 3.0), MaskEvidence::kNone);
  EXPECT_EQ(maskEvidence(mask, holes, -1, 4, 3.0), MaskEvidence::kNone);
  EXPECT_EQ(maskEvidence(mask, holes, 4, 9.6, 3.0), MaskEvidence::kNone);
}

}  // namespace
}  // namespace amos::tracking
