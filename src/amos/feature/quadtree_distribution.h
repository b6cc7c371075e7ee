#pragma once
// Spreads keypoints evenly over an image region (ORB-SLAM2's DistributeOctTree idea): the region is split into
// quadrants recursively, most populated nodes first, until there are as many non-empty nodes as wanted; each
// node then keeps its strongest keypoint.
#include <opencv2/core.hpp>

#include <vector>

namespace amos::feature {

// keypoints: candidates inside `region` (points outside are clamped into it). Returns indices into `keypoints`
// of at most `target` kept keypoints, strongest first (ties: lower index first). Deterministic.
std::vector<int> distributeQuadtree(const std::vector<cv::KeyPoint>& keypoints, const cv::Rect2f& region, int target);

}  // namespace amos::feature
