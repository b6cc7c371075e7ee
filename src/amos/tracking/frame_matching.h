#pragma once
// Step "match": a first pose for the frame from matches to the frame before (the motion model's projection
// search from its predictions, pose_prediction.h) or to the reference keyframe (descriptor matching), each
// followed by a pose optimisation that drops the outliers (ORB-SLAM2's TrackWithMotionModel /
// TrackReferenceKeyFrame). Call with Map::mutex() held (shared).
#include <vector>

#include "amos/map/frame.h"
#include "amos/map/keyframe.h"
#include "amos/map/map_point.h"
#include "amos/tracking/pose_prediction.h"
#include "amos/tracking/tracker_options.h"

namespace amos::tracking {

// RGB-D visual odometry: gives the last frame's keypoints with depth but no map point a temporary point (not in
// the map; closest first, all close ones and at least min_points), so the motion-model search has more to match.
// The points are also appended to `temporaries`, which keeps them alive for the frame.
void addTemporaryPoints(map::Frame& last, int min_points, std::vector<map::MapPointPtr>& temporaries);

// Drops the matches pose optimisation flagged as outliers; returns the remaining matches to points in the map.
int discardOutliers(map::Frame& frame);

struct MotionModelMatch {
  bool tracked = false;        // at least Tracking.minMapMatches inliers in the map
  bool used_external = false;  // the best prediction was the external pose (also when tracking then failed)
};

// Tries each prediction in turn: projects the last frame's matched points into the frame (Tracking.
// motionSearchRadius, twice that below motionMinMatches), keeps the prediction with the most matches and
// optimises the pose from it.
MotionModelMatch trackWithMotionModel(map::Frame& frame, const map::Frame& last,
                                      const std::vector<PosePrediction>& predictions, const TrackerOptions& options);

// Matches the frame to the reference keyframe by descriptors (Tracking.referenceMinMatches needed) and optimises
// the pose from T_prior (the last frame's).
bool trackReferenceKeyFrame(map::Frame& frame, const map::KeyFrame& reference, const core::SE3& T_prior,
                            const TrackerOptions& options);

}  // namespace amos::tracking
