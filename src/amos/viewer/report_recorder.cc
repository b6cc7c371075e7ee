#include "amos/viewer/report_recorder.h"

#include "amos/report/mask_outputs.h"
#include "amos/report/run_report.h"
#include "amos/viewer/frame_image.h"

namespace amos::viewer {

ReportRecorder::ReportRecorder(std::size_t overlay_count, int overlay_width)
    : overlay_count_(overlay_count), overlay_width_(overlay_width) {}

void ReportRecorder::onStart(const run::RunStart& start) {
  ground_truth_ = start.ground_truth;
  culled_.start(start.map);
  if (start.total_frames > 0) {
    overlay_frames_ = report::evenlySpacedFrames(start.total_frames, overlay_count_);
  }
}

void ReportRecorder::onFrame(const run::FrameSnapshot& f) {
  ReportFrame r;
  r.index = f.index;
  r.timestamp = f.timestamp;
  r.state = tracking::toString(f.state);
  r.extract_ms = f.extract_ms;
  r.build_ms = f.build_ms;
  r.track_ms = f.track_ms;
  r.frame_ms = f.frame_ms;
  r.keypoints = static_cast<int>(f.keypoints.size());
  r.removed = f.keypoints_removed;
  addFrame(std::move(r), f.bgr, f.dynamic_mask, f.keypoints);
}

void ReportRecorder::addFrame(ReportFrame frame, const cv::Mat& bgr, const cv::Mat& dynamic_mask,
                              const std::vector<cv::Point2f>& keypoints) {
  const std::size_t index = frame.index;
  const double timestamp = frame.timestamp;
  frames_.push_back(std::move(frame));
  bool picked = false;
  if (overlay_frames_.empty()) {
    picked = index % 150 == 75 && overlays_.size() < 2 * overlay_count_;
  } else if (next_overlay_ < overlay_frames_.size() && index >= overlay_frames_[next_overlay_]) {
    picked = true;
    while (next_overlay_ < overlay_frames_.size() && overlay_frames_[next_overlay_] <= index) ++next_overlay_;
  }
  if (picked && !bgr.empty())
    overlays_.push_back(
        {index, timestamp, encodeJpeg(renderFrameOverlay(bgr, dynamic_mask, keypoints, overlay_width_), 80)});
}

void ReportRecorder::onEnd(const std::vector<io::StampedPose>& trajectory, const report::RunInfo& info) {
  trajectory_ = trajectory;
  evaluation_ = info.evaluation;
  culled_points_ = culled_.finish();
}

}  // namespace amos::viewer
