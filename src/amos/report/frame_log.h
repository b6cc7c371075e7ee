#pragma once
// The run's per-frame files, one line per processed frame, as `amos-slam run` appends them while it goes
// (run/live_log.h) and amos::Slam::writeOutputs writes them whole from the frames it kept (api/run_outputs.h):
//   trajectory_live.txt  TUM format (T_wc), every frame tracked (state ok) with its pose at tracking time
//   frames.tsv           every processed frame: index, time stamp, rgb file, tracking state, inliers, keyframe, ms
// One format for both, so the two writers give the same lines for the same frames.
#include <cstddef>
#include <string>
#include <vector>

#include "amos/core/pose.h"
#include "amos/report/run_report.h"
#include "amos/system/dynamic_pipeline.h"
#include "amos/tracking/tracker.h"

namespace amos::report {

inline constexpr const char* kLiveTrajectoryFile = "trajectory_live.txt";
inline constexpr const char* kFramesFile = "frames.tsv";
inline constexpr const char* kFramesHeader = "# index\ttimestamp\trgb_file\tstate\tinliers\tkeyframe\tframe_ms\n";

// What the per-frame files say of one processed frame.
struct FrameRecord {
  std::size_t index = 0;  // 0-based position in the stream
  double timestamp = 0;
  std::string rgb_file;
  tracking::TrackingState state = tracking::TrackingState::kNotInitialized;
  core::SE3 T_cw = core::SE3::Identity();  // at tracking time (meaningful when state is ok)
  int inliers = 0;
  bool new_keyframe = false;
  double frame_ms = 0;  // wall time since the frame before was done
};

// The record of a frame as the pipeline returned it (frame_ms left 0: the caller's clock).
FrameRecord frameRecord(const system::ProcessedFrame& out);

// frames.tsv's line of a frame.
std::string framesLine(const FrameRecord& frame);
// trajectory_live.txt's line of a frame: its pose at tracking time, "" when it was not tracked.
std::string liveTrajectoryLine(const FrameRecord& frame);

// Writes both files into `dir` (an existing folder) from `frames`, each whole under a temporary name and renamed:
// the lines the run appended for the same frames. Throws core::Error naming the file that cannot be written.
void writeFrameLogs(const std::string& dir, const std::vector<FrameRecord>& frames);

// Counts a processed frame into the run's depth dropouts (stats.json "depth_dropouts") when its depth was one.
void countDepthDropout(const system::ProcessedFrame& out, DepthDropouts& dropouts);

}  // namespace amos::report
