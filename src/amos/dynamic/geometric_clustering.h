#pragma once
// Geometric clusters (paper Section III-B): k-means over the superpixels' image position and depth, so that a
// cluster is a compact piece of the scene (neighbouring superpixels at similar depth) whose superpixels are
// assumed to share one motion. Deterministic: k-means++ seeding from a fixed seed, then Lloyd iterations.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "amos/dynamic/boundary_assignment.h"
#include "amos/dynamic/depth_slic.h"

namespace amos::dynamic {

struct ClusteringOptions {
  // Dynamic.Cluster.count: m. 16 clusters on a 640x480 frame are ~140 px cells (~0.75 m across at 3 m with
  // f ~ 540 px): about the size of a person's torso or a chair, the moving things the geometric stage looks for,
  // while each cluster still holds ~19 of the 300 superpixels and enough tracked corners to score.
  int num_clusters = 16;
  // Dynamic.Cluster.depthScale: depth difference [m] weighing as much as one cluster cell of image distance.
  // A cell (~140 px) spans ~0.75 m at a typical indoor range of 3 m, so 0.75 m keeps clusters about as deep as
  // they are wide: objects in front of a wall separate from it, a sloped floor is cut into patches.
  double depth_scale_m = 0.75;
  // Dynamic.Cluster.maxIterations: Lloyd rounds; assignments of a few hundred points settle in ~10.
  int max_iterations = 20;
  // Dynamic.Cluster.seed: k-means++ seed (fixed for reproducible runs).
  unsigned seed = 42;
  void check() const;
};

// A point for k-means: image position (pixels) and depth (metres, 0 = unknown: the depth dimension is then left
// out of its distances and of the centre update).
struct ClusterPoint {
  float x = 0, y = 0, depth = 0;
};

// Assigns each point a cluster in [0, k) with k = min(num_clusters, points.size()). image_size sets the cell
// size used to normalise positions. Returns the labels; deterministic for given options.
std::vector<int> kmeansClusters(const std::vector<ClusterPoint>& points, cv::Size image_size,
                                const ClusteringOptions& options);

// Convenience: clusters the superpixels (writes Superpixel::cluster) and returns the per-pixel cluster map
// (CV_32S, same size as segmentation.labels).
cv::Mat clusterSuperpixels(SuperpixelSegmentation& segmentation, const ClusteringOptions& options);

// The geometric partition of one frame (III-B): its depth-SLIC superpixels, clustered, and the per-pixel cluster
// map. It needs only that frame's colour and depth, so it can be computed ahead of time (e.g. for the next frame
// in a look-ahead worker) and handed to DynamicFrontEnd through FrontEndInput::partition.
struct GeometricPartition {
  SuperpixelSegmentation segmentation;  // Superpixel::cluster filled in
  cv::Mat cluster_map;                  // CV_32S cluster of every pixel
  double superpixel_ms = 0, cluster_ms = 0;  // time the two steps took
  // Adjacency and occlusion edges of the superpixels, when computed ahead with the partition (else the mask
  // building computes them).
  std::optional<SuperpixelGraph> graph;
};
GeometricPartition computeGeometricPartition(const cv::Mat& bgr, const cv::Mat& depth,
                                             const DepthSlicOptions& superpixel_options,
                                             const ClusteringOptions& cluster_options);

// Number of clusters in use (1 + the largest Superpixel::cluster; 0 when there are no superpixels).
int clusterCount(const SuperpixelSegmentation& segmentation);

}  // namespace amos::dynamic
