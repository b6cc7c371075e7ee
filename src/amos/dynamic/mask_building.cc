#include "amos/dynamic/mask_building.h"

#include "amos/core/error.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace amos::dynamic {

namespace {

// Depth [m] at the pixel nearest p, 0 when invalid or outside the image.
float depthAt(const cv::Mat& depth, cv::Point2f p) {
  const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
  if (x < 0 || y < 0 || x >= depth.cols || y >= depth.rows) return 0.f;
  const float z = depth.at<float>(y, x);
  return std::isfinite(z) && z > 0.f ? z : 0.f;
}

// Whether the (2 r + 1)^2 window around p holds an occlusion edge: two adjacent valid depths differing by more than
// `ratio` of the nearer one (holes are skipped). Adjacent pixels, not the window's range, so that a slanted surface
// (a floor, a box face seen obliquely: a few mm per pixel) does not count.
bool depthEdgeInWindow(const cv::Mat& depth, cv::Point2f p, int r, double ratio) {
  const int cx = static_cast<int>(std::lround(p.x)), cy = static_cast<int>(std::lround(p.y));
  const int x0 = std::max(0, cx - r), x1 = std::min(depth.cols - 1, cx + r);
  const int y0 = std::max(0, cy - r), y1 = std::min(depth.rows - 1, cy + r);
  auto jump = [ratio](float a, float b) {
    return a > 0.f && b > 0.f && std::fabs(a - b) > ratio * std::min(a, b);  // NaN compares false: skipped
  };
  for (int y = y0; y <= y1; ++y) {
    const float* row = depth.ptr<float>(y);
    const float* below = y < y1 ? depth.ptr<float>(y + 1) : nullptr;
    for (int x = x0; x <= x1; ++x) {
      if (x < x1 && jump(row[x], row[x + 1])) return true;
      if (below && jump(row[x], below[x])) return true;
    }
  }
  return false;
}

}  // namespace

void markLabelledPixels(const cv::Mat& label_map, const std::vector<bool>& marked, cv::Mat& mask) {
  // Bytes instead of vector<bool>'s bits: looked up for every pixel of the frame.
  const std::vector<uchar> value(marked.begin(), marked.end());
  for (int y = 0; y < mask.rows; ++y) {
    const int* label = label_map.ptr<int>(y);
    uchar* m = mask.ptr<uchar>(y);
    for (int x = 0; x < mask.cols; ++x)
      if (value[label[x]]) m[x] = 255;
  }
}

std::vector<TrackEvidence> seedingEvidence(const JudgedTracks& judged, const cv::Mat& last_depth,
                                           const cv::Mat& depth, const SuperpixelSegmentation& segmentation,
                                           double static_bar_px, const DynamicOptions& options) {
  const std::vector<PointTrack>& tracks = judged.tracks;
  const TrackPoints& lifted = judged.lifted;
  const std::vector<std::optional<Eigen::Vector2d>>& residuals = judged.residuals;
  const std::vector<double>& epipolar_px = judged.epipolar_px;
  // A track moves with what fills its LK window. When the window (in either frame) holds an occlusion edge
  // (a depth step beyond the depth-edge ratio) that may be the other side's motion: a wall corner next to a
  // moving box follows the box. Such a track, or one whose current pixel shows another surface than its last
  // one, would seed the wrong superpixel; it abstains.
  const double ratio = options.reprojection.depth_edge_ratio;
  const int half_window = options.tracking.lk_window / 2;
  std::vector<TrackEvidence> evidence;
  evidence.reserve(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const PointTrack& t = tracks[i];
    const float z_last = depthAt(last_depth, t.last), z_now = depthAt(depth, t.current);
    const int s = labelAt(segmentation.labels, t.current);
    const float z_superpixel = s >= 0 ? segmentation.superpixels[s].depth : 0.f;
    if ((z_last > 0 && z_now > 0 && std::fabs(z_now - z_last) > ratio * z_last) ||
        depthEdgeInWindow(last_depth, t.last, half_window, ratio) ||
        depthEdgeInWindow(depth, t.current, half_window, ratio)) {
      // Except when no depth of its window lets it be static: then the edge itself moved, and an edge moves
      // with its occluding (near) side. It then votes, by its motion only, for its superpixel if that is the
      // near side.
      const auto& intervals = lifted.intervals;
      if (!lifted.points_w[i] && !intervals.empty() && intervals[i] && residuals[i] &&
          residuals[i]->norm() >= static_bar_px && z_superpixel > 0 &&
          z_superpixel <= (1 + ratio) * intervals[i]->near_m)
        evidence.push_back({t.current, residuals[i], 0.0});
      continue;
    }
    // Nor does one that lies off its superpixel's surface: where a superpixel straddles the mover's border (its
    // outline is found at a coarser scale), the track belongs to the other side.
    if (z_now > 0 && z_superpixel > 0 && std::fabs(z_now - z_superpixel) > ratio * std::min(z_now, z_superpixel))
      continue;
    evidence.push_back({t.current, residuals[i], epipolar_px[i]});
  }
  return evidence;
}

std::vector<bool> dynamicSuperpixels(const SuperpixelFrame& frame, const ClusterVerdicts& verdicts,
                                     const TrackSeeds& tracks, const DynamicOptions& options,
                                     const SuperpixelEvidence& moving) {
  const SuperpixelSegmentation& segmentation = frame.segmentation;
  const cv::Mat& depth = frame.depth;
  const SuperpixelGraph* graph = frame.graph;
  const std::vector<bool>& border = verdicts.border;
  const std::vector<bool>& dynamic_cluster = verdicts.dynamic_cluster;
  const std::vector<TrackEvidence>& evidence = tracks.evidence;
  const double static_bar_px = tracks.static_bar_px;
  const bool seed_outside = tracks.seed_outside;
  const std::vector<bool>& depth_moving = moving.depth_moving;
  const std::vector<bool>& baseline_moving = moving.baseline_moving;
  const std::vector<int>& baseline_points = moving.baseline_points;
  const SurfaceSeeds& surface_seeds = moving.surface_seeds;
  const int count = static_cast<int>(segmentation.superpixels.size());
  SuperpixelGraph computed;
  if (graph == nullptr) computed = superpixelGraph(segmentation, depth, options.reprojection.depth_edge_ratio);
  const SuperpixelGraph& g = graph != nullptr ? *graph : computed;
  const auto& neighbours = g.neighbours;
  std::vector<RegionLabel> seeds =
      seedSuperpixels(segmentation, neighbours, border, dynamic_cluster, evidence,
                      SeedBars{static_bar_px, options.epipolar.dynamic_threshold_px},
                      SeedOptions{seed_outside, options.epipolar.min_dynamic_points});
  for (std::size_t s = 0; s < depth_moving.size() && s < seeds.size(); ++s)
    if (depth_moving[s] && seeds[s] == RegionLabel::kUnlabelled && !(s < border.size() && border[s]))
      seeds[s] = RegionLabel::kDynamic;
  for (std::size_t s = 0; s < baseline_moving.size() && s < seeds.size(); ++s)
    if (baseline_moving[s] && !(s < border.size() && border[s])) seeds[s] = RegionLabel::kDynamic;
  std::vector<bool> may_be_dynamic(count);
  for (int s = 0; s < count; ++s)
    may_be_dynamic[s] = dynamic_cluster[segmentation.superpixels[s].cluster] || seeds[s] == RegionLabel::kDynamic;
  if (std::find(surface_seeds.seeds.begin(), surface_seeds.seeds.end(), true) != surface_seeds.seeds.end()) {
    const SurfaceSimilarity similarity{options.superpixel.colour_scale, options.superpixel.depth_scale_m,
                                       options.baseline_tracks.grow_dissimilarity};
    const std::vector<bool> surface =
        surfaceFromMovingSeeds(segmentation.superpixels, g, seeds, border, surface_seeds, baseline_points, similarity);
    for (int s = 0; s < count; ++s) may_be_dynamic[s] = may_be_dynamic[s] || surface[s];
  }
  const std::vector<RegionLabel> labels =
      growRegions(segmentation.superpixels, neighbours, seeds, may_be_dynamic, options.superpixel.colour_scale,
                  options.superpixel.depth_scale_m, g.occlusion_edges);
  std::vector<bool> dynamic(count);
  for (int s = 0; s < count; ++s) dynamic[s] = labels[s] == RegionLabel::kDynamic;
  return dynamic;
}

std::vector<bool> surfaceFromMovingSeeds(const std::vector<Superpixel>& superpixels, const SuperpixelGraph& graph,
                                         const std::vector<RegionLabel>& seeds, const std::vector<bool>& border,
                                         const SurfaceSeeds& moving, const std::vector<int>& baseline_points,
                                         const SurfaceSimilarity& similarity) {
  const std::vector<bool>& moving_seeds = moving.seeds;
  const std::vector<bool>& within = moving.within;
  const double colour_scale = similarity.colour_scale, depth_scale_m = similarity.depth_scale_m;
  const double max_dissimilarity = similarity.max_dissimilarity;
  const std::size_t count = superpixels.size();
  core::require(graph.neighbours.size() == count && seeds.size() == count,
                "surfaceFromMovingSeeds: the graph and the seeds must be of these superpixels");
  auto flag = [](const std::vector<bool>& v, std::size_t s) { return s < v.size() && v[s]; };
  std::vector<bool> reached(count, false);
  std::vector<int> queue;
  for (std::size_t s = 0; s < count; ++s)
    if (flag(moving_seeds, s) && !flag(border, s)) {
      reached[s] = true;
      queue.push_back(static_cast<int>(s));
    }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int s = queue[head];
    const std::vector<int>& neighbours = graph.neighbours[s];
    for (std::size_t k = 0; k < neighbours.size(); ++k) {
      const int n = neighbours[k];
      if (reached[n] || graph.occlusion_edges[s][k] || flag(border, n)) continue;
      if (!within.empty() && !flag(within, n)) continue;
      // Measured superpixels speak for themselves: a track's vote or a long-baseline point that did not move.
      if (seeds[n] != RegionLabel::kUnlabelled) continue;
      if (n < static_cast<int>(baseline_points.size()) && baseline_points[n] > 0) continue;
      if (superpixelDissimilarity(superpixels[s], superpixels[n], colour_scale, depth_scale_m) > max_dissimilarity)
        continue;
      reached[n] = true;
      queue.push_back(n);
    }
  }
  return reached;
}

DynamicMask buildDynamicMask(const MaskStages& stages, const SuperpixelEvidence& moving, const DynamicOptions& options,
                             DynamicDiagnostics& diag) {
  const FrontEndInput& in = stages.in;
  const GeometricPartition& partition = stages.partition;
  const DecisionRegions& regions = stages.regions;
  const PoseConfirmation& confirmation = stages.confirmation;
  const ClusterVoting& voting = stages.voting;
  const std::vector<bool>& depth_moving = moving.depth_moving;
  const std::vector<bool>& baseline_moving = moving.baseline_moving;
  DynamicMask out;
  out.mask = cv::Mat(in.gray.size(), CV_8U, cv::Scalar(0));
  const SuperpixelSegmentation& segmentation = partition.segmentation;
  const bool any_dynamic_cluster =
      std::find(voting.dynamic_cluster.begin(), voting.dynamic_cluster.end(), true) != voting.dynamic_cluster.end();
  const bool seed_outside = options.boundary.seed_outside_clusters && confirmation.refit.ok;
  const bool any_moving = std::find(depth_moving.begin(), depth_moving.end(), true) != depth_moving.end() ||
                          std::find(baseline_moving.begin(), baseline_moving.end(), true) != baseline_moving.end();
  if (options.boundary.superpixel_mask && (any_dynamic_cluster || seed_outside || any_moving)) {
    // Per superpixel (boundary_assignment.h): seeds from the tracks, then seeded region growing.
    std::vector<TrackEvidence> evidence =
        seedingEvidence({stages.tracks, stages.candidates.lifted, confirmation.residuals, stages.epipolar.distance_px},
                        in.last_depth, in.depth, segmentation, confirmation.static_bar_px, options);
    // Tracks outside the decision map (the border blocks, or the edge band of the per-track border rule) abstain.
    evidence.erase(std::remove_if(evidence.begin(), evidence.end(),
                                  [&](const TrackEvidence& t) { return labelAt(regions.decision_map, t.pixel) < 0; }),
                   evidence.end());
    out.dynamic_superpixel =
        dynamicSuperpixels({segmentation, in.depth, partition.graph ? &*partition.graph : nullptr},
                           {regions.border, voting.dynamic_cluster},
                           {evidence, confirmation.static_bar_px, seed_outside}, options, moving);
    diag.dynamic_superpixels =
        static_cast<int>(std::count(out.dynamic_superpixel.begin(), out.dynamic_superpixel.end(), true));
    markLabelledPixels(segmentation.labels, out.dynamic_superpixel, out.mask);
  } else {
    // The mask covers whole dynamic clusters, border blocks included (they only abstain from the decision).
    markLabelledPixels(partition.cluster_map, voting.dynamic_cluster, out.mask);
  }
  return out;
}

}  // namespace amos::dynamic
