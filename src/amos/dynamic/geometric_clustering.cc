#include "amos/dynamic/geometric_clustering.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/core/stage_timer.h"

namespace amos::dynamic {

void ClusteringOptions::check() const {
  core::requireAtLeast(num_clusters, "num_clusters", 1);
  core::requirePositive(depth_scale_m, "depth_scale_m");
  core::requireAtLeast(max_iterations, "max_iterations", 1);
}

namespace {

struct ClusterCentre {
  double x = 0, y = 0, depth = 0;
  bool has_depth = false;
};

// Squared normalised distance; the depth dimension counts only when both sides know their depth.
double distance2(const ClusterPoint& p, const ClusterCentre& c, double inv_cell, double inv_depth) {
  const double dx = (p.x - c.x) * inv_cell, dy = (p.y - c.y) * inv_cell;
  double d2 = dx * dx + dy * dy;
  if (p.depth > 0 && c.has_depth) {
    const double dz = (p.depth - c.depth) * inv_depth;
    d2 += dz * dz;
  }
  return d2;
}

ClusterCentre centreAt(const ClusterPoint& p) { return {p.x, p.y, p.depth, p.depth > 0}; }

// Uniform double in [0, 1) straight from the engine's bits, so the sequence is the same on every standard library.
double uniform01(std::mt19937& rng) { return rng() / 4294967296.0; }

}  // namespace

std::vector<int> kmeansClusters(const std::vector<ClusterPoint>& points, cv::Size image_size,
                                const ClusteringOptions& options) {
  options.check();
  core::require(image_size.area() > 0, "kmeansClusters: image size must be positive");
  const int n = static_cast<int>(points.size());
  std::vector<int> labels(n, 0);
  if (n == 0) return labels;
  const int k = std::min(options.num_clusters, n);
  // Positions are measured in cluster cells (the side of a square holding 1/k of the image).
  const double inv_cell = 1.0 / std::sqrt(static_cast<double>(image_size.area()) / k);
  const double inv_depth = 1.0 / options.depth_scale_m;

  // k-means++ seeding: each new centre is drawn with probability proportional to the squared distance to the
  // nearest centre chosen so far.
  std::mt19937 rng(options.seed);
  std::vector<ClusterCentre> centres;
  centres.reserve(k);
  centres.push_back(centreAt(points[static_cast<std::size_t>(uniform01(rng) * n)]));
  std::vector<double> nearest(n, std::numeric_limits<double>::max());
  while (static_cast<int>(centres.size()) < k) {
    double total = 0;
    for (int i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], distance2(points[i], centres.back(), inv_cell, inv_depth));
      total += nearest[i];
    }
    int pick = n - 1;
    if (total > 0) {
      double target = uniform01(rng) * total;
      for (int i = 0; i < n; ++i) {
        target -= nearest[i];
        if (target < 0) {
          pick = i;
          break;
        }
      }
    } else {
      pick = static_cast<int>(centres.size());  // all points coincide with centres: any distinct index
    }
    centres.push_back(centreAt(points[pick]));
  }

  // Lloyd iterations until no assignment changes.
  std::vector<int> assigned(n, -1);
  for (int it = 0; it < options.max_iterations; ++it) {
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      int best = 0;
      double best_d = std::numeric_limits<double>::max();
      for (int c = 0; c < k; ++c) {
        const double d = distance2(points[i], centres[c], inv_cell, inv_depth);
        if (d < best_d) best_d = d, best = c;
      }
      if (best != assigned[i]) assigned[i] = best, changed = true;
    }
    if (!changed && it > 0) break;
    std::vector<double> sx(k, 0), sy(k, 0), sz(k, 0);
    std::vector<int> count(k, 0), count_z(k, 0);
    for (int i = 0; i < n; ++i) {
      const int c = assigned[i];
      sx[c] += points[i].x, sy[c] += points[i].y, ++count[c];
      if (points[i].depth > 0) sz[c] += points[i].depth, ++count_z[c];
    }
    for (int c = 0; c < k; ++c) {
      if (count[c] == 0) {
        // An empty cluster restarts at the point worst served by its centre (deterministic).
        int worst = 0;
        double worst_d = -1;
        for (int i = 0; i < n; ++i) {
          const double d = distance2(points[i], centres[assigned[i]], inv_cell, inv_depth);
          if (d > worst_d) worst_d = d, worst = i;
        }
        centres[c] = centreAt(points[worst]);
        continue;
      }
      centres[c].x = sx[c] / count[c];
      centres[c].y = sy[c] / count[c];
      centres[c].has_depth = count_z[c] > 0;
      centres[c].depth = count_z[c] > 0 ? sz[c] / count_z[c] : 0;
    }
  }
  for (int i = 0; i < n; ++i) labels[i] = assigned[i];
  return labels;
}

cv::Mat clusterSuperpixels(SuperpixelSegmentation& segmentation, const ClusteringOptions& options) {
  std::vector<ClusterPoint> points;
  points.reserve(segmentation.superpixels.size());
  for (const Superpixel& s : segmentation.superpixels) points.push_back({s.x, s.y, s.depth});
  const std::vector<int> labels = kmeansClusters(points, segmentation.labels.size(), options);
  for (std::size_t i = 0; i < labels.size(); ++i) segmentation.superpixels[i].cluster = labels[i];
  cv::Mat cluster_map(segmentation.labels.size(), CV_32S);
  for (int y = 0; y < cluster_map.rows; ++y) {
    const int* sp = segmentation.labels.ptr<int>(y);
    int* out = cluster_map.ptr<int>(y);
    for (int x = 0; x < cluster_map.cols; ++x) out[x] = labels[sp[x]];
  }
  return cluster_map;
}

int clusterCount(const SuperpixelSegmentation& segmentation) {
  int count = 0;
  for (const Superpixel& s : segmentation.superpixels) count = std::max(count, s.cluster + 1);
  return count;
}

GeometricPartition computeGeometricPartition(const cv::Mat& bgr, const cv::Mat& depth,
                                             const DepthSlicOptions& superpixel_options,
                                             const ClusteringOptions& cluster_options) {
  GeometricPartition partition;
  core::Stopwatch watch;
  partition.segmentation = computeDepthSlic(bgr, depth, superpixel_options);
  partition.superpixel_ms = watch.elapsedMs();
  watch.restart();
  partition.cluster_map = clusterSuperpixels(partition.segmentation, cluster_options);
  partition.cluster_ms = watch.elapsedMs();
  return partition;
}

}  // namespace amos::dynamic
