#pragma once
// Boundary handling of the geometric module (paper III-C, last paragraphs): epipolar violators tend to sit on
// the borders of moving objects, where the cluster under the point may be the static background. Such a point
// is given to the cluster around it (within ~30 px) whose mean reprojection error is the largest. Superpixel
// blocks touching the image border take no part in the decision.
#include <opencv2/core.hpp>
#include <vector>

namespace amos::dynamic {

struct BoundaryOptions {
  // Dynamic.Boundary.radius: the paper's 30 px, about one superpixel step at 640x480 (S ~ 32 px for 300
  // superpixels): far enough to reach the cluster on the other side of the border the point sits on, not so far
  // as to jump over a whole cluster (~140 px cells).
  int search_radius_px = 30;
  // Dynamic.Boundary.borderMargin: a superpixel is a border block when it comes within this many pixels of the
  // image edge. 0 = touching the edge, as in the paper: those blocks are cut by the image frame, so their
  // corners track worst (LK windows leave the image, content enters and leaves the view).
  int border_margin_px = 0;
  void check() const;
};

// Marks the superpixels (labels CV_32S in [0, count)) that reach within margin_px of the image edge.
std::vector<bool> borderSuperpixels(const cv::Mat& superpixel_labels, int count, int margin_px);

// The cluster map used for decisions: the per-pixel cluster map with the border blocks set to -1.
cv::Mat decisionClusterMap(const cv::Mat& cluster_map, const cv::Mat& superpixel_labels,
                           const std::vector<bool>& border_superpixels);

// The cluster a dynamic point at pixel p counts for: among the clusters found within radius_px of p in
// decision_map (CV_32S, -1 = ignored), the one with the largest cluster_error (ties: the cluster under p, then
// the lower id). Returns -1 when the disc holds no cluster.
int assignToNeighbourCluster(cv::Point2f p, const cv::Mat& decision_map, const std::vector<double>& cluster_error,
                             int radius_px);

}  // namespace amos::dynamic
