#pragma once
// The run's work as it goes, for any end of the program (SIGKILL included), as an observer: after each processed
// frame one line is appended to each of two files in the output folder and handed to the operating system at once
// (io/line_log.h), so a killed run leaves both, valid, up to the last frame tracked:
//   trajectory_live.txt  TUM format (T_wc), every frame tracked (state ok) with its pose at tracking time
//   frames.tsv           every processed frame: index, time stamp, rgb file, tracking state, inliers, keyframe, ms
// The pose at tracking time is not the final one: trajectory.txt, written at the end, holds each frame's pose
// relative to its reference keyframe after local / global bundle adjustment and loop closing, and the lost frames
// too. Cost per frame: two small write(2) calls. The lines' format is report/frame_log.h's, which
// amos::Slam::writeOutputs writes the same files with.
#include <memory>
#include <string>

#include "amos/io/line_log.h"
#include "amos/report/frame_log.h"
#include "amos/run/run_observer.h"

namespace amos::run {

class LiveLog : public RunObserver {
 public:
  // Creates both files in `dir` (an existing folder); throws core::Error naming the one that cannot be written.
  explicit LiveLog(const std::string& dir);

  static constexpr const char* kTrajectoryFile = report::kLiveTrajectoryFile;
  static constexpr const char* kFramesFile = report::kFramesFile;

  // Appends the frame's lines. A write error (a full disk) is a warning, once; the run goes on without these
  // files and still writes its final ones.
  void onFrame(const FrameSnapshot& frame) override;

 private:
  std::unique_ptr<io::LineLog> trajectory_, frames_;
};

}  // namespace amos::run
