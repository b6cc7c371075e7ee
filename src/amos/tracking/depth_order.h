#pragma once
// The order in which tracking turns a frame's depth into points: closest first, all the close ones and at least a
// minimum (the motion model's temporary points, a new keyframe's map points).
#include <utility>
#include <vector>

#include "amos/map/frame.h"

namespace amos::tracking {

// (depth, keypoint index) of the keypoints with valid depth, closest first.
std::vector<std::pair<float, int>> keypointsByDepth(const map::FrameFeatures& f);

}  // namespace amos::tracking
