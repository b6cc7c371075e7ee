#pragma once
// Duplicate fusion (ORB-SLAM2's SearchInNeighbors / Fuse): the keyframe's points are projected into its first and
// second covisibility neighbours and vice versa; a point that lands on a keypoint with a matching descriptor
// either adds that observation or, when the keypoint already has a point, the two are merged (the one with more
// observations survives). Call with Map::mutex() held exclusively.
#include "amos/map/map.h"

namespace amos::match {

struct FusionOptions {
  int neighbors = 10;         // Mapping.fuseNeighbors
  int second_neighbors = 5;   // Mapping.fuseSecondNeighbors
  double radius = 3;          // Mapping.fuseRadius: window in pixels x scale
  int max_distance = 50;      // Mapping.fuseMaxDistance: Hamming (ORB-SLAM2 TH_LOW)
  void check() const;
};

// Projects `points` into `kf`; returns the number of fused / added observations.
int fusePoints(map::Map& map, const map::KeyFramePtr& kf, const std::vector<map::MapPointPtr>& points,
               const FusionOptions& options);

// The whole neighbourhood step for a new keyframe, ending with its connections updated.
int fuseWithNeighbors(map::Map& map, const map::KeyFramePtr& kf, const FusionOptions& options);

}  // namespace amos::match
