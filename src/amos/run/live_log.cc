#include "amos/run/live_log.h"

#include <spdlog/spdlog.h>

#include <filesystem>

#include "amos/core/error.h"
#include "amos/io/trajectory.h"
#include "amos/report/frame_log.h"

namespace amos::run {

LiveLog::LiveLog(const std::string& dir)
    : trajectory_(std::make_unique<io::LineLog>((std::filesystem::path(dir) / kTrajectoryFile).string(),
                                                io::kTumTrajectoryHeader)),
      frames_(std::make_unique<io::LineLog>((std::filesystem::path(dir) / kFramesFile).string(),
                                            report::kFramesHeader)) {}

void LiveLog::onFrame(const FrameSnapshot& frame) {
  if (!trajectory_) return;
  try {
    const report::FrameRecord record{frame.index, frame.timestamp,    frame.rgb_file,     frame.state,
                                     frame.T_cw,  frame.inliers,      frame.new_keyframe, frame.frame_ms};
    // frames.tsv first: a kill between the two writes leaves no pose without its frame line.
    frames_->append(report::framesLine(record));
    if (const std::string line = report::liveTrajectoryLine(record); !line.empty()) trajectory_->append(line);
  } catch (const core::Error& e) {
    spdlog::warn("{}; {} and {} are not written further (the final outputs are still written at the end)", e.what(),
                 kTrajectoryFile, kFramesFile);
    trajectory_.reset();
    frames_.reset();
  }
}

}  // namespace amos::run
