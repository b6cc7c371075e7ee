#include "amos/run/mask_scoring.h"

#include <spdlog/spdlog.h>

#include <utility>

namespace amos::run {

MaskScoring::MaskScoring(eval::GroundTruthMasks truth, bool keep_truth)
    : truth_(std::move(truth)), keep_truth_(keep_truth) {
  for (const eval::GroundTruthInstance& inst : truth_.instances())
    instance_accuracy_.describe(inst.id, inst.category, inst.name);
}

void MaskScoring::onFrame(const FrameSnapshot& frame) {
  frame_truth_ = cv::Mat();
  if (!keep_truth_ && frame.dynamic_mask.empty()) return;
  if (const auto k = truth_.frameAt(frame.timestamp)) {
    const cv::Mat ids = truth_.instanceMask(*k);
    const std::vector<bool> moving = truth_.movingIds(*k);
    frame_truth_ = eval::GroundTruthMasks::moverMask(ids, moving);
    if (!frame.dynamic_mask.empty()) instance_accuracy_.add(*k, frame.dynamic_mask, ids, moving);
  }
  if (!frame_truth_.empty() && !frame.dynamic_mask.empty()) {
    mask_accuracy_.add(frame.dynamic_mask, frame_truth_);
    const eval::MaskCounts& c = mask_accuracy_.perFrame().back();
    spdlog::debug("frame {}: dynamic mask against the truth: {} true, {} found, {} wrongly marked", frame.index,
                  c.true_positive + c.false_negative, c.true_positive, c.false_positive);
  }
}

void MaskScoring::addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) {
  (void)trajectory;
  if (!mask_accuracy_.empty()) info.mask_accuracy = mask_accuracy_.summary();
  if (!instance_accuracy_.empty()) info.instance_accuracy = instance_accuracy_.summary();
}

}  // namespace amos::run
