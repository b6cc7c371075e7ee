#pragma once
// Descriptor matching between a frame and the map, guided by projection (ORB-SLAM2's SearchByProjection family)
// or by brute force when no pose prior is good enough (reference-keyframe tracking and relocalisation, standing in
// for bag-of-words matching). All functions read map points and keyframes: call them with Map::mutex() held
// (shared is enough). Matches are written into frame.map_points.
#include <memory>
#include <unordered_set>
#include <vector>

#include "amos/map/frame.h"
#include "amos/map/keyframe.h"
#include "amos/map/map_point.h"

namespace amos::tracking {

struct MatchingOptions {
  int th_high = 100;            // max Hamming distance for projection matches
  int th_low = 50;              // max Hamming distance for brute-force matches
  float local_ratio = 0.8f;     // best / second-best on the same level (local map search)
  float brute_force_ratio = 0.7f;  // Lowe ratio for brute-force matching against a keyframe
  bool check_orientation = true;   // keep matches in the three dominant rotation bins
  void check() const;
};

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
int searchLastFrame(map::Frame& current, const map::Frame& last, double th, const MatchingOptions& options);

// Local-map search: projected points (not yet matched in the frame) within th * (2.5 or 4) * scale pixels.
int searchLocalPoints(map::Frame& frame, const std::vector<ProjectedPoint>& points, double th,
                      const MatchingOptions& options);

// Keyframe points projected with the frame's pose (relocalisation); points in `already` are skipped.
int searchKeyFrameByProjection(map::Frame& frame, const map::KeyFrame& kf,
                               const std::unordered_set<const map::MapPoint*>& already, double th, int max_distance,
                               const MatchingOptions& options);

// Brute-force matching of the frame's descriptors against the keyframe's keypoints that carry good map points
// (ratio test, th_low, rotation consistency). Returns per frame keypoint the matched map point (or null).
std::vector<map::MapPointPtr> matchFrameToKeyFrame(const map::Frame& frame, const map::KeyFrame& kf, float ratio,
                                                   const MatchingOptions& options, int* num_matches);

// Keeps the matches whose keypoint rotation difference falls in the three most populated of 30 histogram bins
// (ORB-SLAM2's rotation consistency check). `rotation_deltas[k]` belongs to match k; returns the kept flags.
std::vector<bool> rotationConsistent(const std::vector<float>& rotation_deltas_deg);

}  // namespace amos::tracking
