#include "amos/report/mover_diagnosis.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"

namespace amos::report {
namespace {

// A 40 x 20 grey frame: the truth's mover is the left half, the mask covers the middle 20 columns; one dynamic
// cluster (the right half) and three tracks: below the threshold, far beyond it, unscored.
struct Scene {
  cv::Mat bgr = cv::Mat(20, 40, CV_8UC3, cv::Scalar(100, 100, 100));
  cv::Mat truth = cv::Mat(20, 40, CV_16U, cv::Scalar(0));
  dynamic::FrontEndResult out;
  Scene() {
    truth.colRange(0, 20).setTo(3);
    out.mask = cv::Mat(20, 40, CV_8U, cv::Scalar(0));
    out.mask.colRange(10, 30).setTo(255);
    out.cluster_map = cv::Mat(20, 40, CV_32S, cv::Scalar(0));
    out.cluster_map.colRange(20, 40).setTo(1);
    out.dynamic_cluster = {false, true};
    out.diagnostics.confirm_threshold_px = 1.0;
    out.tracks = {{{5, 5}, {5, 5}}, {{35, 15}, {35, 15}}, {{5, 15}, {5, 15}}};
    out.judged_error_px = {0.2, 9.0, std::nullopt};
  }
};

TEST(DecisionPicture, TintsTheMaskAgainstTheTruthAndColoursTheTracksByError) {
  Scene s;
  const cv::Mat pic = decisionPicture(s.bgr, s.truth, s.out);
  ASSERT_EQ(pic.size(), s.bgr.size());
  ASSERT_EQ(pic.type(), CV_8UC3);
  // (BGR) mover marked: green; static marked: red; mover missed: blue; static unmarked: the dimmed frame.
  const cv::Vec3b hit = pic.at<cv::Vec3b>(10, 15), wrong = pic.at<cv::Vec3b>(10, 25), miss = pic.at<cv::Vec3b>(10, 2),
                  plain = pic.at<cv::Vec3b>(3, 36);
  EXPECT_GT(hit[1], hit[0] + 100);
  EXPECT_GT(hit[1], hit[2] + 100);
  EXPECT_GT(wrong[2], wrong[1] + 100);
  EXPECT_GT(miss[0], miss[2] + 100);
  EXPECT_EQ(plain, cv::Vec3b(60, 60, 60));
  // The dynamic cluster's outline is white.
  EXPECT_EQ(pic.at<cv::Vec3b>(0, 20), cv::Vec3b(255, 255, 255));
  // Tracks: green below the threshold, red beyond three times it, grey unscored.
  EXPECT_EQ(pic.at<cv::Vec3b>(5, 5), cv::Vec3b(0, 255, 0));
  EXPECT_EQ(pic.at<cv::Vec3b>(15, 35), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(pic.at<cv::Vec3b>(15, 5), cv::Vec3b(160, 160, 160));
}

TEST(DecisionPicture, RefusesAMaskOfAnotherSize) {
  Scene s;
  s.out.mask = cv::Mat(10, 10, CV_8U, cv::Scalar(0));
  EXPECT_THROW(decisionPicture(s.bgr, s.truth, s.out), core::Error);
}

}  // namespace
}  // namespace amos::report
