#pragma once
// Mask scoring as an observer: every processed frame's final dynamic mask against the sequence's ground-truth
// movers (synthetic sequences: masks.txt, masks/, instances.json; eval/ground_truth_masks.h), pixel by pixel and
// per mover instance, into RunInfo::mask_accuracy and RunInfo::instance_accuracy.
#include <opencv2/core.hpp>

#include <vector>

#include "amos/eval/ground_truth_masks.h"
#include "amos/eval/instance_mask_metrics.h"
#include "amos/eval/mask_metrics.h"
#include "amos/run/run_observer.h"

namespace amos::run {

class MaskScoring : public RunObserver {
 public:
  // keep_truth: also look up the frame's true mover mask when the front end made no mask (mode none), for the
  // overlays of MaskWriting (frameTruth()).
  MaskScoring(eval::GroundTruthMasks truth, bool keep_truth);

  void onFrame(const FrameSnapshot& frame) override;
  void addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) override;

  // The true mover mask (CV_8U, 255 = a moving instance) of the frame last given to onFrame; empty when the
  // ground truth has no frame at its time stamp or it was not looked up.
  const cv::Mat& frameTruth() const { return frame_truth_; }

 private:
  eval::GroundTruthMasks truth_;
  bool keep_truth_;
  cv::Mat frame_truth_;
  eval::MaskAccuracyAccumulator mask_accuracy_;
  eval::InstanceAccuracyAccumulator instance_accuracy_;
};

}  // namespace amos::run
