#pragma once
// A trajectory's poses looked up by a frame's time stamp: the dense map's final fusion (in-memory stamps) and the
// seen-through share (stamps read back from trajectory.txt, rounded by its format) both place frames this way.
#include <cmath>
#include <map>
#include <vector>

#include "amos/core/pose.h"
#include "amos/io/trajectory.h"

namespace amos::io {

using PosesByStamp = std::map<double, core::SE3>;  // T_wc by time stamp (s)

inline PosesByStamp posesByStamp(const std::vector<StampedPose>& trajectory) {
  PosesByStamp out;
  for (const StampedPose& pose : trajectory) out.emplace(pose.timestamp, pose.T_wc);
  return out;
}

// The pose whose stamp lies within `tolerance` seconds of `stamp` (the same frame's), or nullptr.
inline const core::SE3* poseNear(const PosesByStamp& poses, double stamp, double tolerance) {
  const auto it = poses.lower_bound(stamp - tolerance);
  if (it == poses.end() || std::abs(it->first - stamp) > tolerance) return nullptr;
  return &it->second;
}

}  // namespace amos::io
