#include "amos/report/frame_log.h"

#include <fmt/format.h>

#include <filesystem>

#include "amos/io/atomic_file.h"
#include "amos/io/trajectory.h"

namespace amos::report {

FrameRecord frameRecord(const system::ProcessedFrame& out) {
  const tracking::TrackResult& t = out.slam.track;
  return {out.frame.index, out.frame.timestamp, out.frame.rgb_file, t.state, t.T_cw, t.inliers, t.new_keyframe, 0.0};
}

std::string framesLine(const FrameRecord& f) {
  return fmt::format("{}\t{:.6f}\t{}\t{}\t{}\t{}\t{:.1f}\n", f.index, f.timestamp, f.rgb_file,
                     tracking::toString(f.state), f.inliers, f.new_keyframe ? 1 : 0, f.frame_ms);
}

std::string liveTrajectoryLine(const FrameRecord& f) {
  if (f.state != tracking::TrackingState::kOk) return {};
  return io::formatTumPose({f.timestamp, f.T_cw.inverse()});
}

void writeFrameLogs(const std::string& dir, const std::vector<FrameRecord>& frames) {
  std::string trajectory = io::kTumTrajectoryHeader, lines = kFramesHeader;
  for (const FrameRecord& f : frames) {
    trajectory += liveTrajectoryLine(f);
    lines += framesLine(f);
  }
  const std::filesystem::path d(dir);
  io::writeFileAtomically((d / kLiveTrajectoryFile).string(), trajectory);
  io::writeFileAtomically((d / kFramesFile).string(), lines);
}

void countDepthDropout(const system::ProcessedFrame& out, DepthDropouts& d) {
  if (!out.frame.depth_dropout) return;
  ++d.frames;
  d.tracked += out.slam.track.state == tracking::TrackingState::kOk;
  d.lost += out.slam.track.state == tracking::TrackingState::kLost;
}

}  // namespace amos::report
