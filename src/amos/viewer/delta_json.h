#pragma once
// JSON of what the browsers receive: an update event (new / moved / removed points and keyframes, appended
// trajectory, the frame status) and the pieces of the whole state. Positions are rounded to the millimetre to keep
// the messages small. Shapes (see docs/viewer.md):
//   point     [id, x, y, z]            keyframe  [id, x, y, z, qx, qy, qz, qw]  (T_wc)
//   trajectory point [t, x, y, z]
#include <nlohmann/json.hpp>

#include "amos/run/run_observer.h"
#include "amos/viewer/live_update.h"

namespace amos::viewer {

nlohmann::json pointJson(const PointSample& p);
nlohmann::json keyFrameJson(const KeyFrameSample& k);
nlohmann::json trajectoryJson(const std::vector<TrajectoryPoint>& points);

// {"seq", "points": [...], "removed": [ids], "culled": [...], "keyframes": [...], "removed_keyframes": [ids],
//  "trajectory": [...], "trajectory_reset", "ground_truth", "frame", "info", "summary", "frame_image"}; absent
// members did not change.
nlohmann::json updateJson(const LiveUpdate& update, std::uint64_t seq);

// {"index", "total", "processed", "timestamp", "state", "inliers", "keyframe", "keypoints", "removed", "fps",
//  "times_ms": {"extract", "build", "track", "frame"}, "T_wc": [x, y, z, qx, qy, qz, qw]}; fps over the frames since
// the previous status (`fps`, computed by the caller).
nlohmann::json frameStatusJson(const run::FrameSnapshot& frame, double fps);

}  // namespace amos::viewer
