#pragma once
// A frame's pose from its matches to map points: EPnP RANSAC on the matches and pose optimisation on the frame's
// current matches. Tracking, relocalisation and loop verification all use these. Read map points: call with
// Map::mutex() held (shared is enough).
#include <vector>

#include "amos/geometry/pnp_ransac.h"
#include "amos/geometry/pose_optimizer.h"
#include "amos/map/frame.h"
#include "amos/map/map_point.h"

namespace amos::match {

// The pose optimiser's observation of keypoint i and its matched map point (which must be set): undistorted pixel,
// virtual right coordinate, the information of the keypoint's pyramid level.
geometry::PoseObservation poseObservationOf(const map::Frame& frame, std::size_t i);

// Runs pose optimisation on the frame's current matches from frame.T_cw, writes pose and outlier flags back.
// Returns the number of inliers.
int optimizeFramePose(map::Frame& frame, const geometry::PoseOptimizerOptions& options);

// optimizeFramePose, then the outlier matches are removed from the frame. Returns the number of inliers.
int optimizeFramePoseDroppingOutliers(map::Frame& frame, const geometry::PoseOptimizerOptions& options);

// PnP RANSAC on the frame's keypoints matched to `matches` (per keypoint, null = none). On success the frame
// takes the PnP pose and keeps only the inlier matches; returns the number of inliers (0 on failure, frame
// unchanged). Relocalisation and loop verification both start from this.
int poseFromMatchesByPnp(map::Frame& frame, const std::vector<map::MapPointPtr>& matches,
                         const geometry::PnpRansacOptions& options);

}  // namespace amos::match
