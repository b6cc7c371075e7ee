#include "amos/run/mask_writing.h"

#include <utility>

namespace amos::run {

MaskWriting::MaskWriting(std::string dir, std::size_t overlay_count, const MaskScoring* truth)
    : dir_(std::move(dir)), overlay_count_(overlay_count), truth_(truth) {}

void MaskWriting::onStart(const RunStart& start) { writer_.emplace(dir_, start.total_frames, overlay_count_); }

void MaskWriting::onFrame(const FrameSnapshot& frame) {
  const cv::Mat truth = truth_ != nullptr ? truth_->frameTruth() : cv::Mat();
  writer_->add(frame.index, frame.rgb_file, frame.bgr, frame.dynamic_mask, frame.prior_mask, truth);
}

}  // namespace amos::run
