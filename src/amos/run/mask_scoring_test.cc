#include "amos/run/mask_scoring.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "amos/run/observer_test_frames.h"

namespace amos::run {
namespace {

// Driven alone with a synthetic sequence's frames and its ground-truth movers: a mask that is the truth scores 1,
// an empty-handed one (nothing marked) scores recall 0; a frame without a mask is not scored.
TEST(MaskScoring, ScoresTheDynamicMaskAgainstTheTrueMovers) {
  const std::string dir = testing::syntheticSequence("walking_static", 4);
  auto truth = eval::GroundTruthMasks::find(dir);
  ASSERT_TRUE(truth);
  const eval::GroundTruthMasks reference = *truth;
  MaskScoring perfect(*truth, false), blind(*truth, false), unmasked(*truth, false);
  for (FrameSnapshot f : testing::snapshotsOf(dir)) {
    const auto k = reference.frameAt(f.timestamp);
    ASSERT_TRUE(k);
    unmasked.onFrame(f);
    EXPECT_TRUE(unmasked.frameTruth().empty());
    f.dynamic_mask = reference.moverMask(*k);
    perfect.onFrame(f);
    EXPECT_EQ(cv::countNonZero(perfect.frameTruth() != f.dynamic_mask), 0);
    f.dynamic_mask = cv::Mat::zeros(f.dynamic_mask.size(), CV_8U);
    blind.onFrame(f);
  }
  report::RunInfo perfect_info, blind_info, unmasked_info;
  perfect.addToInfo({}, perfect_info);
  blind.addToInfo({}, blind_info);
  unmasked.addToInfo({}, unmasked_info);
  ASSERT_TRUE(perfect_info.mask_accuracy);
  EXPECT_EQ(perfect_info.mask_accuracy->frames, 4u);
  EXPECT_GT(perfect_info.mask_accuracy->frames_with_truth, 0u);
  EXPECT_DOUBLE_EQ(perfect_info.mask_accuracy->recall, 1.0);
  EXPECT_DOUBLE_EQ(perfect_info.mask_accuracy->precision, 1.0);
  EXPECT_FALSE(perfect_info.instance_accuracy.empty());
  ASSERT_TRUE(blind_info.mask_accuracy);
  EXPECT_DOUBLE_EQ(blind_info.mask_accuracy->recall, 0.0);
  EXPECT_FALSE(unmasked_info.mask_accuracy);
  EXPECT_TRUE(unmasked_info.instance_accuracy.empty());
}

// keep_truth (for the overlays of --save-masks): the truth is looked up even for a frame without a mask.
TEST(MaskScoring, KeepsTheTruthForTheMaskWriterWhenAsked) {
  const std::string dir = testing::syntheticSequence("walking_static", 4);
  auto truth = eval::GroundTruthMasks::find(dir);
  ASSERT_TRUE(truth);
  MaskScoring scoring(*truth, true);
  const FrameSnapshot f = testing::snapshotsOf(dir).front();
  scoring.onFrame(f);
  EXPECT_FALSE(scoring.frameTruth().empty());
  report::RunInfo info;
  scoring.addToInfo({}, info);
  EXPECT_FALSE(info.mask_accuracy);
}

}  // namespace
}  // namespace amos::run
