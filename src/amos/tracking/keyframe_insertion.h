#pragma once
// Step "commit" (a keyframe): the frame made a keyframe in the map, with map points from its depth. Takes the
// map's exclusive lock; local mapping gets the keyframe afterwards (KeyFrameSink).
#include <optional>
#include <vector>

#include "amos/map/frame.h"
#include "amos/map/keyframe.h"
#include "amos/map/map.h"
#include "amos/map/map_point.h"
#include "amos/tracking/photometric_refiner.h"

namespace amos::tracking {

struct NewKeyFrame {
  map::KeyFramePtr kf;
  std::vector<map::MapPointPtr> new_points;  // created from the frame's depth
};

// The map's first keyframe: the frame (at its pose) with a point for every keypoint with depth. photometric (may
// be null) gets the keyframe's template.
NewKeyFrame insertFirstKeyFrame(map::Map& map, map::Frame& frame, PhotometricRefiner* photometric);

struct KeyFrameInsertion {
  int new_points_min = 100;                         // Tracking.newPointsMin
  PhotometricRefiner* photometric = nullptr;        // gets the keyframe's template (null: none)
  const map::PoseLink* photometric_link = nullptr;  // the frame's pose link to its reference (null: none)
};

// A keyframe from a tracked frame: its matches become observations (matches to bad points, or to points the
// keyframe already observes, are dropped from the frame too), and unmatched keypoints with depth become map points,
// closest first: all close ones and at least new_points_min.
NewKeyFrame insertKeyFrame(map::Map& map, map::Frame& frame, const KeyFrameInsertion& insertion);

}  // namespace amos::tracking
