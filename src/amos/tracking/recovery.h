#pragma once
// Recovery of a recently lost frame near where the camera was (ORB-SLAM3's "recently lost" state): the last local
// map searched in a wide window (Tracking.recoverySearchRadius) around each prediction (pose_prediction.h), the
// pose from PnP RANSAC on the matches, then optimised. Call with Map::mutex() held (shared).
#include <vector>

#include "amos/core/pose.h"
#include "amos/map/frame.h"
#include "amos/tracking/local_map.h"
#include "amos/tracking/tracker_options.h"

namespace amos::tracking {

// True, with frame's pose and inlier matches set, when some prediction leads to Tracking.relocMinInliers inliers;
// otherwise the frame is left without matches.
bool recoverNearPredictions(map::Frame& frame, const std::vector<core::SE3>& predictions, const LocalMap& local_map,
                            const TrackerOptions& options);

}  // namespace amos::tracking
