#pragma once
// Step "predict": the poses a frame's search starts from, before any matching (ORB-SLAM2's constant-velocity
// model). Pure functions of what tracking remembers of the frames before.
#include <optional>
#include <vector>

#include "amos/core/pose.h"
#include "amos/map/ids.h"
#include "amos/tracking/tracker_options.h"

namespace amos::tracking {

struct PosePrediction {
  core::SE3 T_cw = core::SE3::Identity();
  bool external = false;  // supplied from outside (the dynamic front end), not by the motion model
};

// What the motion model knows of the last frame.
struct MotionHistory {
  core::SE3 last_T_cw = core::SE3::Identity();  // the last frame's pose
  bool last_tracked = false;                    // whether that pose was tracked (not carried over a loss)
  std::optional<core::SE3> velocity;            // T_last_beforelast, the motion from the frame before to the last
};

// The motion-model search's starting poses, in the order tried: the external pose (if any), the last pose moved
// on by the velocity (unless the external pose replaces it, ExternalPosePolicy::kReplace), and the last tracked
// pose itself when there is neither (no velocity yet: the frame right after a relocalisation).
std::vector<PosePrediction> motionModelPredictions(const MotionHistory& history,
                                                   const std::optional<core::SE3>& external, ExternalPosePolicy policy);

// The last frame that was tracked, kept while tracking is lost.
struct LastTrackedPose {
  core::SE3 T_cw = core::SE3::Identity();
  map::FrameId frame = 0;
  std::optional<core::SE3> velocity;  // the motion model's velocity at that frame
};

// Where a recently lost camera may be at frame `frame`, in the order tried: the external pose (if any), the last
// tracked pose carried on by its velocity over the frames since (a camera that kept moving while the view was
// covered), and the last tracked pose (one that stopped).
std::vector<core::SE3> recoveryPredictions(const LastTrackedPose& last, map::FrameId frame,
                                           const std::optional<core::SE3>& external);

}  // namespace amos::tracking
