#pragma once
// Collects, while a run goes, what report.html shows per frame: stage times, keypoints removed by the dynamic
// mask, tracking state, and a strip of small mask overlays of evenly spaced frames (JPEG, encoded when the frame
// passes: 8 frames of the run, ~1 ms each), and in a thread of its own the map points removed as dynamic
// (culled_recorder.h). A run::RunObserver; everything else comes at the end (onEnd).
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "amos/eval/evaluate.h"
#include "amos/run/run_observer.h"
#include "amos/viewer/culled_recorder.h"

namespace amos::viewer {

struct ReportFrame {
  std::size_t index = 0;
  double timestamp = 0;
  std::string state;
  double extract_ms = 0, build_ms = 0, track_ms = 0, frame_ms = 0;
  int keypoints = 0, removed = 0;
};

struct ReportOverlay {
  std::size_t index = 0;
  double timestamp = 0;
  std::vector<unsigned char> jpeg;
};

class ReportRecorder : public run::RunObserver {
 public:
  explicit ReportRecorder(std::size_t overlay_count = 8, int overlay_width = 240);
  void onStart(const run::RunStart& start) override;
  void onFrame(const run::FrameSnapshot& frame) override;
  void onEnd(const std::vector<io::StampedPose>& trajectory, const report::RunInfo& info) override;
  // onFrame's work for a caller without run::FrameSnapshot (amos_slam_node, from amos::Slam's FrameResult): the
  // frame's figures, and its colour image, dynamic mask and keypoints for the strip of overlays (may be empty).
  void addFrame(ReportFrame frame, const cv::Mat& bgr, const cv::Mat& dynamic_mask,
                const std::vector<cv::Point2f>& keypoints);

  const std::vector<ReportFrame>& frames() const { return frames_; }
  const std::vector<ReportOverlay>& overlays() const { return overlays_; }
  const std::vector<io::StampedPose>& trajectory() const { return trajectory_; }
  const std::optional<eval::EvaluationResult>& evaluation() const { return evaluation_; }
  // The map points removed as dynamic over the run (culled_recorder.h), known after onEnd.
  const std::vector<PointSample>& culledPoints() const { return culled_points_; }
  // The sequence's ground truth (RunStart::ground_truth, camera poses in its own frame); empty when none.
  const std::vector<io::StampedPose>& groundTruth() const { return ground_truth_; }

 private:
  std::size_t overlay_count_;
  int overlay_width_;
  // Frame indices the strip should show, ascending; a frame that was not processed (dropped by --realtime) is
  // replaced by the next processed one. Empty for a live source: every 150th frame instead.
  std::vector<std::size_t> overlay_frames_;
  std::size_t next_overlay_ = 0;
  std::vector<ReportFrame> frames_;
  std::vector<ReportOverlay> overlays_;
  std::vector<io::StampedPose> trajectory_, ground_truth_;
  std::optional<eval::EvaluationResult> evaluation_;
  std::vector<PointSample> culled_points_;
  CulledPointRecorder culled_;
};

}  // namespace amos::viewer
