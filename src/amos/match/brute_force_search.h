#pragma once
// Matching a frame to a keyframe without a pose prior (standing in for ORB-SLAM2's bag-of-words
// SearchByBoW): reference-keyframe tracking, relocalisation and loop detection start from it. Reads map points and
// keyframes: call with Map::mutex() held (shared is enough).
#include <vector>

#include "amos/map/frame.h"
#include "amos/map/keyframe.h"
#include "amos/map/map_point.h"
#include "amos/match/matching_options.h"

namespace amos::match {

// Brute-force matching of the frame's descriptors against the keyframe's keypoints that carry good map points
// (ratio test, th_low, rotation consistency). Returns per frame keypoint the matched map point (or null).
std::vector<map::MapPointPtr> matchFrameToKeyFrame(const map::Frame& frame, const map::KeyFrame& kf, float ratio,
                                                   const MatchingOptions& options, int* num_matches);

}  // namespace amos::match
