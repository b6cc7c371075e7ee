#pragma once
// What a run shows to those who watch it while it goes without the run depending on any of them: the run's own
// outputs (evaluation, mask scoring, mask writing, recording: the other files of this module) and the caller's
// observers (the live web viewer, the report.html recorder; SequenceRunOptions::observers). The controller
// (controller.h) calls them in the order they were added: onStart, onFrame per processed frame, then, once the
// stream has ended, onStreamEnd, addToInfo and onEnd.
//
// Contract (the run's speed must not depend on its observers):
//   - onFrame is called in the run's thread after every processed frame and must return at once: copy what it
//     needs (FrameSnapshot is cheap to copy: the images are shared cv::Mat headers of the frame's own pixels,
//     which nothing writes after the frame was read), hand it to its own thread, never wait for a consumer.
//   - RunStart::map is shared with tracking and local mapping: read it only under a shared lock of map->mutex(),
//     briefly (an exclusive writer waits for the lock). It is a shared_ptr, so an observer's thread that still
//     holds it when a run ends early by an exception never reads a destroyed map; release it in onEnd.
#include <opencv2/core.hpp>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/io/trajectory.h"
#include "amos/io/dataset.h"
#include "amos/map/map.h"
#include "amos/report/run_report.h"
#include "amos/tracking/tracker.h"

namespace amos::run {

struct RunStart {
  std::shared_ptr<const map::Map> map;
  core::CameraIntrinsics camera;
  std::size_t total_frames = 0;  // 0 = live source
  std::string sequence, mode;
  // --load-map: the map file the run started from ("" = an empty map) and whether it only localises in it.
  std::string loaded_map;
  bool localize = false;
  // The sequence's ground truth as camera poses (T_wc; Bonn marker poses already converted), empty when none.
  std::vector<io::StampedPose> ground_truth;
};

struct FrameSnapshot {
  std::size_t index = 0;      // 0-based position of the frame in the stream
  std::size_t total = 0;      // frames in the stream, 0 = live
  std::size_t processed = 0;  // frames processed so far, this one included
  double timestamp = 0;
  std::string rgb_file;
  tracking::TrackingState state = tracking::TrackingState::kNotInitialized;
  core::SE3 T_cw = core::SE3::Identity();
  bool new_keyframe = false;
  int inliers = 0;
  cv::Mat bgr;           // the colour image (shared pixels)
  cv::Mat dynamic_mask;  // CV_8U, 255 = dynamic; empty in mode none (shared pixels)
  cv::Mat prior_mask;    // the undilated person mask; empty without segmentation (shared pixels)
  std::vector<cv::Point2f> keypoints;  // as detected (image pixels), before the mask removed any
  int keypoints_removed = 0;           // of those, removed by the dynamic mask
  double extract_ms = 0, build_ms = 0, track_ms = 0;  // SLAM stages of this frame
  double frame_ms = 0;     // wall time since the previous frame was done (1000 / instantaneous fps)
  double elapsed_s = 0;    // since the run started
  // The frame as the source delivered it (colour and depth, time stamps; shared pixels), for the observers that
  // write it out (recording).
  io::RgbdFrame frame;
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // Before the first frame is read.
  virtual void onStart(const RunStart& start) { (void)start; }
  // In the run's thread after every processed frame; returns at once (see the contract above).
  virtual void onFrame(const FrameSnapshot& frame) = 0;
  // After the last frame was processed and the pipeline finished: complete what this observer writes (the
  // recording's queued frames). An exception here ends the run as failed (the first error is kept), with its
  // outputs written as for any failure.
  virtual void onStreamEnd() {}
  // Then, with the final trajectory: add what this observer measured to the run's info (the evaluation, the mask
  // accuracy). An exception here is the run's (runSequence throws it).
  virtual void addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) {
    (void)trajectory;
    (void)info;
  }
  // After the last frame: mapping stopped, `trajectory` is final (T_wc of every processed frame, with the map's
  // corrections), `info` has the evaluation when there was ground truth. Not called when the run ends by an
  // exception.
  virtual void onEnd(const std::vector<io::StampedPose>& trajectory, const report::RunInfo& info) {
    (void)trajectory;
    (void)info;
  }
};

}  // namespace amos::run
