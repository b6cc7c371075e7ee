#pragma once
// Step "commit" (the frame): what tracking keeps of a frame once its pose is settled: the motion model's velocity,
// the frame's matches cleaned for the next frame's search and for a keyframe, and its pose relative to its
// reference keyframe (T_cr = T_cw * T_wr), through which later map corrections reach the trajectory.
#include <optional>

#include "amos/core/pose.h"
#include "amos/map/frame.h"
#include "amos/map/ids.h"
#include "amos/map/map.h"

namespace amos::tracking {

struct MotionStep {
  bool tracked = false;       // this frame was tracked
  bool relocalized = false;   // ... by relocalisation or recovery: its pose does not continue the last one's
  bool last_tracked = false;  // the last frame was tracked
  core::SE3 T_cw = core::SE3::Identity();       // this frame's pose
  core::SE3 last_T_cw = core::SE3::Identity();  // the last frame's
};

// The constant-velocity model after the frame: the motion from the last frame to it (T_cur_last) when both were
// tracked and it continues the last; none after a loss or a relocalisation; unchanged otherwise.
std::optional<core::SE3> nextVelocity(const std::optional<core::SE3>& velocity, const MotionStep& step);

// Drops the matches to temporary points (visual odometry, not in the map): they do not survive the frame.
void dropTemporaryMatches(map::Frame& frame);
// Drops the matches flagged as outliers and clears the flags: outliers take no part in a keyframe nor in the next
// frame's motion-model search.
void dropOutlierMatches(map::Frame& frame);

struct ReferenceAnchoring {
  bool tracked = false;
  bool own_keyframe = false;                             // the frame was just made a keyframe (its own reference)
  map::KeyFrameId reference_kf = map::kNoKeyFrame;       // tracked: the reference keyframe
  map::KeyFrameId last_reference_kf = map::kNoKeyFrame;  // the last frame's (kept while lost)
  core::SE3 last_T_cr = core::SE3::Identity();           // the last frame's pose relative to it
};

// Sets frame.reference_kf and returns the frame's T_cr: a tracked frame's measured against its reference keyframe
// (the identity for its own keyframe); a lost frame keeps the last T_cr (as ORB-SLAM2 does) and takes its pose
// from it, so the trajectory still has a line per frame (none before the first frame localised in a loaded map).
// Call with Map::mutex() held (shared).
core::SE3 anchorToReference(map::Frame& frame, const ReferenceAnchoring& anchoring, const map::Map& map);

}  // namespace amos::tracking
