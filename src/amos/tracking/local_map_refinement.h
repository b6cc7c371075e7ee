#pragma once
// Step "refine" (features): the frame's first pose made precise against the local map (ORB-SLAM2's
// TrackLocalMap): the local map is rebuilt around the frame's matches, its points searched in the frame, the pose
// optimised on all matches, and the inliers that are map points counted. Call with Map::mutex() held (shared).
#include "amos/map/frame.h"
#include "amos/map/map.h"
#include "amos/tracking/local_map.h"
#include "amos/tracking/tracker_options.h"

namespace amos::tracking {

// How the search and the acceptance depend on the frame (narrower windows and lower bars away from a
// relocalisation).
struct LocalMapSearch {
  double radius = 3;     // Tracking.localSearchRadius, or relocSearchRadius right after a relocalisation
  int min_inliers = 30;  // Tracking.localMinInliers, or relocMinInliers in the frames after one
};

struct LocalMapRefinement {
  bool tracked = false;        // at least search.min_inliers inliers
  int inliers = 0;             // inlier matches to points in the map
  map::KeyFramePtr reference;  // the keyframe sharing the most points with the frame (null: none)
};

LocalMapRefinement refineWithLocalMap(map::Frame& frame, LocalMap& local_map, const map::Map& map,
                                      const LocalMapSearch& search, const TrackerOptions& options);

// Counts the frame's inliers (matches not flagged outlier) to points in the map, and tells each matched point it
// was found (MapPoint::increaseFound, the found/visible ratio local mapping culls by).
int countFoundInliers(const map::Frame& frame);

}  // namespace amos::tracking
