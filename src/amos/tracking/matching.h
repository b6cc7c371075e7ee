#pragma once
// Tracking's projection searches (ORB-SLAM2's SearchByProjection against the last frame and the local map). The
// searches shared with relocalisation, mapping and loop closing are in match/. All functions read map points: call
// them with Map::mutex() held (shared is enough). Matches are written into frame.map_points.
#include <memory>
#include <vector>

#include "amos/map/frame.h"
#include "amos/map/keyframe.h"
#include "amos/map/map_point.h"
#include "amos/match/matching_options.h"

namespace amos::tracking {

// A local-map point seen from the frame's current pose (ORB-SLAM2's isInFrustum result).
struct ProjectedPoint {
  map::MapPointPtr point;
  double u = 0, v = 0, u_right = 0;
  double z = 0;  // depth in the camera
  int level = 0;
  double view_cos = 1;
};

// Projects a point with the frame's pose; false if behind, outside the image, outside the scale-invariance
// distance range or seen at more than acos(min_view_cos) from its mean viewing direction.
bool projectIntoFrame(const map::Frame& frame, const map::MapPointPtr& p, double min_view_cos, ProjectedPoint& out);

// Motion-model search: the last frame's matched points into the current frame within th * scale pixels, on levels
// consistent with forward/backward motion. Returns the number of new matches.
int searchLastFrame(map::Frame& current, const map::Frame& last, double th, const match::MatchingOptions& options);

// Local-map search: projected points (not yet matched in the frame) within th * (2.5 or 4) * scale pixels.
int searchLocalPoints(map::Frame& frame, const std::vector<ProjectedPoint>& points, double th,
                      const match::MatchingOptions& options);

}  // namespace amos::tracking
