#include "amos/eval/mask_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/core/error.h"

namespace amos::eval {
namespace {

// A 10x10 frame: truth covers columns 0..4 (50 px), the prediction columns 3..7 (50 px): overlap 2 columns.
cv::Mat columns(int from, int to) {
  cv::Mat m(10, 10, CV_8U, cv::Scalar(0));
  m.colRange(from, to + 1).setTo(255);
  return m;
}

TEST(MaskMetrics, CountsOverlappingColumns) {
  const MaskCounts c = compareMasks(columns(3, 7), columns(0, 4));
  EXPECT_EQ(c.true_positive, 20);
  EXPECT_EQ(c.false_positive, 30);
  EXPECT_EQ(c.false_negative, 30);
  EXPECT_EQ(c.true_negative, 20);
  EXPECT_DOUBLE_EQ(precision(c), 0.4);
  EXPECT_DOUBLE_EQ(recall(c), 0.4);
  EXPECT_DOUBLE_EQ(iou(c), 20.0 / 80.0);
}

TEST(MaskMetrics, AnyNonZeroValueIsPositive) {
  cv::Mat predicted = columns(0, 4);
  predicted.setTo(1, predicted != 0);
  const MaskCounts c = compareMasks(predicted, columns(0, 4));
  EXPECT_DOUBLE_EQ(precision(c), 1.0);
  EXPECT_DOUBLE_EQ(recall(c), 1.0);
  EXPECT_DOUBLE_EQ(iou(c), 1.0);
}

TEST(MaskMetrics, UndefinedRatiosAreNaN) {
  const cv::Mat empty(10, 10, CV_8U, cv::Scalar(0));
  const MaskCounts none = compareMasks(empty, empty);
  EXPECT_TRUE(std::isnan(precision(none)));
  EXPECT_TRUE(std::isnan(recall(none)));
  EXPECT_TRUE(std::isnan(iou(none)));
  const MaskCounts missed = compareMasks(empty, columns(0, 0));
  EXPECT_TRUE(std::isnan(precision(missed)));
  EXPECT_DOUBLE_EQ(recall(missed), 0.0);
  EXPECT_DOUBLE_EQ(iou(missed), 0.0);
}

TEST(MaskMetrics, RejectsMismatchedMasks) {
  EXPECT_THROW(compareMasks(cv::Mat(10, 10, CV_8U), cv::Mat(10, 11, CV_8U)), core::Error);
  EXPECT_THROW(compareMasks(cv::Mat(10, 10, CV_16U), cv::Mat(10, 10, CV_8U)), core::Error);
}

TEST(MaskMetrics, PoolsPixelsAndTakesPerFrameMedians) {
  MaskAccuracyAccumulator acc;
  acc.add(columns(0, 4), columns(0, 4));  // perfect: P = R = IoU = 1
  acc.add(columns(3, 7), columns(0, 4));  // P = R = 0.4, IoU = 0.25
  acc.add(columns(0, 9), columns(0, 1));  // P = 0.2, R = 1, IoU = 0.2
  const cv::Mat empty(10, 10, CV_8U, cv::Scalar(0));
  acc.add(empty, empty);  // nothing to find, nothing found: no per-frame value, no pixel counted
  const MaskAccuracy a = acc.summary();
  EXPECT_EQ(a.frames, 4);
  EXPECT_EQ(a.frames_with_truth, 3);
  // Pooled: TP = 50 + 20 + 20 = 90, FP = 0 + 30 + 80 = 110, FN = 0 + 30 + 0 = 30.
  EXPECT_EQ(a.total.true_positive, 90);
  EXPECT_EQ(a.total.false_positive, 110);
  EXPECT_EQ(a.total.false_negative, 30);
  EXPECT_DOUBLE_EQ(a.precision, 90.0 / 200.0);
  EXPECT_DOUBLE_EQ(a.recall, 90.0 / 120.0);
  EXPECT_DOUBLE_EQ(a.iou, 90.0 / 230.0);
  EXPECT_DOUBLE_EQ(a.dynamic_fraction, 200.0 / 400.0);
  // Medians over the three defined frames: P {1, 0.4, 0.2}, R {1, 0.4, 1}, IoU {1, 0.25, 0.2}.
  EXPECT_DOUBLE_EQ(a.median_precision, 0.4);
  EXPECT_DOUBLE_EQ(a.median_recall, 1.0);
  EXPECT_DOUBLE_EQ(a.median_iou, 0.25);
  const nlohmann::json j = toJson(a);
  EXPECT_EQ(j["frames"], 4);
  EXPECT_DOUBLE_EQ(j["recall"].get<double>(), 0.75);
}

TEST(MaskMetrics, EmptyAccumulatorSummarisesToNaN) {
  const MaskAccuracy a = MaskAccuracyAccumulator().summary();
  EXPECT_EQ(a.frames, 0);
  EXPECT_TRUE(std::isnan(a.recall));
  EXPECT_TRUE(toJson(a)["recall"].is_null());
}

}  // namespace
}  // namespace amos::eval
