#include "amos/eval/instance_mask_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/core/error.h"

namespace amos::eval {
namespace {

// 20x20 frame: instance 1 in rows 0..9 x columns 0..9 (100 px), instance 2 in rows 10..19 x columns 10..19.
cv::Mat twoInstances() {
  cv::Mat ids(20, 20, CV_16U, cv::Scalar(0));
  ids(cv::Rect(0, 0, 10, 10)).setTo(1);
  ids(cv::Rect(10, 10, 10, 10)).setTo(2);
  return ids;
}

TEST(InstanceMaskMetrics, SpillOverIsAttributedToTheMoverItTouches) {
  cv::Mat predicted(20, 20, CV_8U, cv::Scalar(0));
  predicted(cv::Rect(0, 0, 12, 5)).setTo(255);    // half of instance 1 plus 10 static pixels beside it
  predicted(cv::Rect(15, 0, 3, 3)).setTo(255);    // 9 static pixels touching no instance
  const auto counts = compareInstanceMasks(predicted, twoInstances(), {false, true, true});
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts[0].id, 1);
  EXPECT_EQ(counts[0].pixels, 100);
  EXPECT_EQ(counts[0].marked, 50);
  EXPECT_EQ(counts[0].attributed_fp, 10);
  EXPECT_EQ(counts[1].marked, 0);
  EXPECT_EQ(counts[1].attributed_fp, 0);
}

TEST(InstanceMaskMetrics, RestingInstanceTakesNoAttribution) {
  cv::Mat predicted(20, 20, CV_8U, cv::Scalar(0));
  predicted(cv::Rect(0, 0, 12, 10)).setTo(255);
  const auto counts = compareInstanceMasks(predicted, twoInstances(), {false, false, true});
  EXPECT_FALSE(counts[0].moving);
  EXPECT_EQ(counts[0].marked, 100);
  EXPECT_EQ(counts[0].attributed_fp, 0);
}

TEST(InstanceMaskMetrics, RecallPrecisionAndReleaseAfterStop) {
  InstanceAccuracyAccumulator acc;
  acc.describe(1, "object", "box");
  const cv::Mat ids = twoInstances();
  cv::Mat all(20, 20, CV_8U, cv::Scalar(0));
  all(cv::Rect(0, 0, 10, 10)).setTo(255);
  const cv::Mat none(20, 20, CV_8U, cv::Scalar(0));
  acc.add(0, all, ids, {false, true, false});   // moving, found
  acc.add(1, none, ids, {false, true, false});  // moving, missed
  acc.add(2, all, ids, {false, false, false});  // stopped, still masked
  acc.add(3, all, ids, {false, false, false});
  acc.add(4, none, ids, {false, false, false});  // released 2 frames after the stop
  acc.add(5, none, ids, {false, false, false});
  const auto summary = acc.summary();
  ASSERT_EQ(summary.size(), 2u);
  const InstanceAccuracy& box = summary[0];
  EXPECT_EQ(box.name, "box");
  EXPECT_EQ(box.moving_frames, 2);
  EXPECT_EQ(box.rest_frames, 4);
  EXPECT_DOUBLE_EQ(box.recall, 0.5);
  EXPECT_DOUBLE_EQ(box.precision, 1.0);
  EXPECT_DOUBLE_EQ(box.rest_marked_fraction, 0.5);
  ASSERT_EQ(box.releases.size(), 1u);
  EXPECT_EQ(box.releases[0].first, 2);
  EXPECT_EQ(box.releases[0].second, 2);
  EXPECT_TRUE(std::isnan(summary[1].recall));  // instance 2 never moved
  const nlohmann::json j = toJson(summary);
  EXPECT_EQ(j[0]["releases"][0]["frames_to_release"], 2);
  EXPECT_TRUE(j[1]["recall"].is_null());
}

TEST(InstanceMaskMetrics, NeverReleasedIsMinusOne) {
  InstanceAccuracyAccumulator acc;
  const cv::Mat ids = twoInstances();
  cv::Mat all(20, 20, CV_8U, cv::Scalar(255));
  acc.add(0, all, ids, {false, true});
  acc.add(1, all, ids, {false, false});
  const auto summary = acc.summary();
  ASSERT_EQ(summary[0].releases.size(), 1u);
  EXPECT_EQ(summary[0].releases[0].second, -1);
}

TEST(InstanceMaskMetrics, RejectsWrongTypes) {
  EXPECT_THROW(compareInstanceMasks(cv::Mat(4, 4, CV_8U), cv::Mat(4, 4, CV_8U), {}), core::Error);
  EXPECT_THROW(compareInstanceMasks(cv::Mat(4, 4, CV_8U), cv::Mat(5, 4, CV_16U), {}), core::Error);
}

}  // namespace
}  // namespace amos::eval
