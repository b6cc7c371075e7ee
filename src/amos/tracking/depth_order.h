#pragma once
// The order in which tracking turns a frame's depth into points: closest first, all the close ones and at least a
// minimum (the motion model's temporary points, a new keyframe's map points).
#include <utility>
#include <vector>

#include "amos/map/frame.h"

namespace amos::tracking {

// (depth, keypoint index) of the keypoints with valid depth, closest first: those at most close_depth away and
// then the next ones up to min_count + 1 in all (or all there are). A loop over it that stops at the first point
// beyond close_depth once it has taken more than min_count sees the same points as over all of them sorted; only
// that prefix is sorted (a partial sort), as the rest would be thrown away.
std::vector<std::pair<float, int>> keypointsByDepth(const map::FrameFeatures& f, double close_depth, int min_count);

}  // namespace amos::tracking
