#pragma once
// New map points between a keyframe and its covisible neighbours (ORB-SLAM2's CreateNewMapPoints): keypoints
// without a map point are matched under the epipolar constraint (brute force instead of bag-of-words nodes),
// then triangulated (or taken from depth when the stereo parallax is larger than the ray parallax) and kept only
// if they lie in front of both cameras, reproject within the chi-square bounds and have consistent scales.
#include <vector>

#include "amos/map/map.h"

namespace amos::mapping {

struct NewPointsOptions {
  int neighbors = 10;          // Mapping.triangulationNeighbors (ORB-SLAM2 RGB-D: 10)
  int max_distance = 50;       // Mapping.triangulationMaxDistance: Hamming (ORB-SLAM2 TH_LOW)
  float ratio = 0.9f;          // Mapping.triangulationRatio: best / second best along the epipolar line
  double max_cos_parallax = 0.9998;  // Mapping.maxCosParallax: rays need at least ~1.1 degrees
  bool check_orientation = true;
  void check() const;
};

// A triangulated candidate, before it is added to the map.
struct NewPointCandidate {
  Eigen::Vector3d position;
  map::KeyFrameId kf1, kf2;
  int idx1, idx2;
};

// Reads the map (call with Map::mutex() held, shared is enough) and returns the candidates.
std::vector<NewPointCandidate> findNewPoints(const map::Map& map, const map::KeyFramePtr& kf,
                                             const NewPointsOptions& options);

// Adds candidates whose keypoint slots are still free (call with Map::mutex() held exclusively).
std::vector<map::MapPointPtr> addNewPoints(map::Map& map, const std::vector<NewPointCandidate>& candidates,
                                           map::FrameId frame);

}  // namespace amos::mapping
