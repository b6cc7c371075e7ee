#include "amos/run/live_log.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>

#include "amos/core/error.h"
#include "amos/io/trajectory.h"

namespace amos::run {

LiveLog::LiveLog(const std::string& dir)
    : trajectory_(std::make_unique<io::LineLog>((std::filesystem::path(dir) / kTrajectoryFile).string(),
                                                io::kTumTrajectoryHeader)),
      frames_(std::make_unique<io::LineLog>(
          (std::filesystem::path(dir) / kFramesFile).string(),
          "# index\ttimestamp\trgb_file\tstate\tinliers\tkeyframe\tframe_ms\n")) {}

void LiveLog::onFrame(const FrameSnapshot& frame) {
  if (!trajectory_) return;
  try {
    // frames.tsv first: a kill between the two writes leaves no pose without its frame line.
    frames_->append(fmt::format("{}\t{:.6f}\t{}\t{}\t{}\t{}\t{:.1f}\n", frame.index, frame.timestamp, frame.rgb_file,
                                tracking::toString(frame.state), frame.inliers, frame.new_keyframe ? 1 : 0,
                                frame.frame_ms));
    if (frame.state == tracking::TrackingState::kOk)
      trajectory_->append(io::formatTumPose({frame.timestamp, frame.T_cw.inverse()}));
  } catch (const core::Error& e) {
    spdlog::warn("{}; {} and {} are not written further (the final outputs are still written at the end)", e.what(),
                 kTrajectoryFile, kFramesFile);
    trajectory_.reset();
    frames_.reset();
  }
}

}  // namespace amos::run
