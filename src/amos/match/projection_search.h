#pragma once
// Projection search of a keyframe's map points into a frame (ORB-SLAM2's SearchByProjection(Frame, KeyFrame)):
// relocalisation and loop verification use it to find more matches once a pose is known. Reads map points and
// keyframes: call with Map::mutex() held (shared is enough). Matches are written into frame.map_points.
#include <unordered_set>
#include <vector>

#include "amos/map/frame.h"
#include "amos/map/keyframe.h"
#include "amos/map/map_point.h"
#include "amos/match/matching_options.h"

namespace amos::match {

// Keyframe points projected with the frame's pose; points in `already` are skipped. Returns the number of new
// matches.
int searchKeyFrameByProjection(map::Frame& frame, const map::KeyFrame& kf,
                               const std::unordered_set<const map::MapPoint*>& already, double th, int max_distance,
                               const MatchingOptions& options);

// The map points the frame is matched to (for projection searches that must skip them).
std::unordered_set<const map::MapPoint*> matchedPoints(const map::Frame& frame);

// The rotation check (rotation_consistency.h) on matches just written into the frame, recorded as (frame keypoint
// index, rotation difference): the rejected ones are cleared and `num_matches` is decreased for each.
void dropRotationInconsistentMatches(map::Frame& frame, const std::vector<int>& indices,
                                     const std::vector<float>& rotation_deltas_deg, int& num_matches);

}  // namespace amos::match
