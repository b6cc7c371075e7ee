#include "amos/dynamic/dynamic_front_end.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/dynamic/candidate_scoring.h"
#include "amos/dynamic/epipolar_evidence.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/pose_confirmation.h"

namespace amos::dynamic {

DynamicFrontEnd::DynamicFrontEnd(const core::PinholeCamera& camera, const DynamicOptions& options)
    : camera_(camera), options_(options) {
  options_.check();
}

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

void checkInput(const DynamicFrameInput& in) {
  core::require(!in.gray.empty() && in.gray.type() == CV_8UC1, "DynamicFrontEnd: gray must be CV_8UC1");
  const cv::Size size = in.gray.size();
  core::require(in.bgr.type() == CV_8UC3 && in.bgr.size() == size, "DynamicFrontEnd: bgr must be CV_8UC3, gray's size");
  core::require(in.depth.type() == CV_32F && in.depth.size() == size,
                "DynamicFrontEnd: depth must be CV_32F metres, gray's size");
  core::require(in.prior_mask.empty() || (in.prior_mask.type() == CV_8UC1 && in.prior_mask.size() == size),
                "DynamicFrontEnd: prior_mask must be empty or CV_8UC1 of the image size");
  core::require(in.last_mask.empty() || (in.last_mask.type() == CV_8UC1 && in.last_mask.size() == size),
                "DynamicFrontEnd: last_mask must be empty or CV_8UC1 of the image size");
  if (!in.last_gray.empty()) {
    core::require(in.last_gray.type() == CV_8UC1 && in.last_gray.size() == size,
                  "DynamicFrontEnd: last_gray must be CV_8UC1 of the image size");
    core::require(in.last_depth.type() == CV_32F && in.last_depth.size() == size,
                  "DynamicFrontEnd: last_depth must be CV_32F of the image size");
  }
}

}  // namespace

DynamicFrameOutput DynamicFrontEnd::process(const DynamicFrameInput& in) const {
  checkInput(in);
  core::Stopwatch total;
  DynamicFrameOutput out;
  out.mask = cv::Mat(in.gray.size(), CV_8U, cv::Scalar(0));
  const DynamicMode mode = options_.mode;
  const bool use_prior = (mode == DynamicMode::kPrior || mode == DynamicMode::kFull) && !in.prior_mask.empty();
  const bool use_geometry = (mode == DynamicMode::kGeometry || mode == DynamicMode::kFull) && !in.last_gray.empty();

  // Prior regions (III-A): connected components of the (already dilated) segmentation mask.
  const PriorRegions prior = use_prior ? findPriorRegions(in.prior_mask) : PriorRegions{};
  const cv::Mat& prior_components = prior.components;
  const int prior_count = prior.count;
  out.diagnostics.prior_regions = prior_count;
  const bool judge_prior = use_prior && use_geometry && options_.judge_prior_regions;
  if (use_prior && !judge_prior) {
    out.mask.setTo(255, in.prior_mask != 0);
    out.diagnostics.dynamic_prior_regions = prior_count;
  }
  if (!use_geometry) {
    out.timings_ms.emplace_back("total", total.elapsedMs());
    return out;
  }
  DynamicDiagnostics& diag = out.diagnostics;
  diag.geometry_ran = true;
  core::Stopwatch stage;
  auto lap = [&](const char* name) {
    out.timings_ms.emplace_back(name, stage.elapsedMs());
    stage.restart();
  };

  // Stage 1a (III-B): superpixels and geometric clusters of the current frame.
  GeometricPartition computed;
  if (in.partition == nullptr) computed = computeGeometricPartition(in.bgr, in.depth, options_.superpixel, options_.cluster);
  const GeometricPartition& partition = in.partition ? *in.partition : computed;
  const SuperpixelSegmentation& segmentation = partition.segmentation;
  out.timings_ms.emplace_back("superpixels", partition.superpixel_ms);
  out.cluster_map = partition.cluster_map;
  stage.restart();
  const int num_clusters = clusterCount(segmentation);
  diag.superpixels = static_cast<int>(segmentation.superpixels.size());
  diag.clusters = num_clusters;
  // Border blocks take no part in the decisions (III-C).
  const DecisionRegions regions =
      findDecisionRegions(segmentation, partition.cluster_map, options_.boundary.border_margin_px);
  const std::vector<bool>& border = regions.border;
  const cv::Mat& decision_map = regions.decision_map;
  out.timings_ms.emplace_back("clusters", partition.cluster_ms + stage.elapsedMs());
  stage.restart();

  // Correspondences last -> current.
  out.tracks = in.tracks ? *in.tracks : trackCorners(in.last_gray, in.gray, options_.tracking);
  diag.tracks = static_cast<int>(out.tracks.size());
  lap("tracking");

  // Stage 1b (III-C, Eq. 5-6): the potential motion regions from the reprojection errors under the initial pose,
  // and every cluster judged again under the pose refitted without them.
  const CandidateScoring candidates =
      scoreCandidates(out.tracks, in, decision_map, num_clusters, prior, camera_, options_, diag);
  const PoseConfirmation confirmation = confirmUnderRefittedPose(out.tracks, candidates, in.T_cw_last, in.T_cw_initial,
                                                                 camera_, options_.reprojection, diag);
  out.reprojection_error_px = candidates.errors_px;
  out.cluster_scores = candidates.cluster_scores;
  out.confirm_scores = confirmation.confirm_scores;
  out.T_cw_judged = confirmation.refit.T_cw;
  const std::vector<std::optional<Eigen::Vector3d>>& points_w = candidates.lifted.points_w;
  const std::vector<std::optional<DepthInterval>>& intervals = candidates.lifted.intervals;
  const std::vector<std::optional<Eigen::Vector2d>>& residuals = confirmation.residuals;
  const std::vector<bool>& outside_candidates = confirmation.fit_tracks;
  std::vector<double> cluster_error(num_clusters);
  for (int c = 0; c < num_clusters; ++c) cluster_error[c] = out.cluster_scores[c].mean_rho;
  auto confirmed = [&](int c) { return confirmation.confirmed[c]; };
  lap("reprojection");

  // Stage 2 (III-C, Eq. 7-8): fundamental matrix on the undistorted tracks outside the potential motion regions,
  // epipolar distance of every track.
  const EpipolarEvidence epipolar =
      fitEpipolarEvidence(out.tracks, outside_candidates, camera_, options_.epipolar, diag);
  out.epipolar_distance_px = epipolar.distance_px;
  lap("epipolar");

  // Decision: each epipolar violator votes for the cluster it belongs to after boundary reassignment and for
  // the prior region it lies in; a candidate region with enough votes is dynamic, and so is a cluster confirmed
  // under the refitted pose. Without F only the confirmation judges.
  std::vector<int> cluster_votes(num_clusters, 0), prior_votes(prior_count + 1, 0);
  for (const cv::Point2f& p : epipolar.violators) {
    if (judge_prior) {
      const int region = labelAt(prior_components, p);
      if (region > 0) ++prior_votes[region];
    }
    if (labelAt(decision_map, p) < 0) continue;  // in a border block
    const int c = assignToNeighbourCluster(p, decision_map, cluster_error, options_.boundary.search_radius_px);
    if (c >= 0) ++cluster_votes[c];
  }
  const int min_votes = options_.epipolar.min_dynamic_points;
  out.dynamic_cluster.assign(num_clusters, false);
  for (int c = 0; c < num_clusters; ++c) {
    out.dynamic_cluster[c] = (out.cluster_scores[c].candidate && cluster_votes[c] >= min_votes) || confirmed(c);
    if (confirmed(c)) ++diag.confirmed_clusters;
    if (out.dynamic_cluster[c]) ++diag.dynamic_clusters;
  }
  out.superpixel_labels = segmentation.labels;
  const bool seed_outside = options_.boundary.seed_outside_clusters && confirmation.refit.ok;
  if (options_.boundary.superpixel_mask && (diag.dynamic_clusters > 0 || seed_outside)) {
    // Per superpixel (boundary_assignment.h): seeds from the tracks, then seeded region growing.
    // A track moves with what fills its LK window. When the window (in either frame) holds an occlusion edge
    // (a depth step beyond the depth-edge ratio) that may be the other side's motion: a wall corner next to a
    // moving box follows the box. Such a track, or one whose current pixel shows another surface than its last
    // one, would seed the wrong superpixel; it abstains.
    const double ratio = options_.reprojection.depth_edge_ratio;
    const int half_window = options_.tracking.lk_window / 2;
    const double static_bar = confirmation.static_bar_px;
    std::vector<TrackEvidence> evidence;
    evidence.reserve(out.tracks.size());
    for (std::size_t i = 0; i < out.tracks.size(); ++i) {
      const PointTrack& t = out.tracks[i];
      const float z_last = depthAt(in.last_depth, t.last), z_now = depthAt(in.depth, t.current);
      const int s = labelAt(segmentation.labels, t.current);
      const float z_superpixel = s >= 0 ? segmentation.superpixels[s].depth : 0.f;
      if ((z_last > 0 && z_now > 0 && std::fabs(z_now - z_last) > ratio * z_last) ||
          depthEdgeInWindow(in.last_depth, t.last, half_window, ratio) ||
          depthEdgeInWindow(in.depth, t.current, half_window, ratio)) {
        // Except when no depth of its window lets it be static: then the edge itself moved, and an edge moves
        // with its occluding (near) side. It then votes, by its motion only, for its superpixel if that is the
        // near side.
        if (!points_w[i] && !intervals.empty() && intervals[i] && residuals[i] && residuals[i]->norm() >= static_bar &&
            z_superpixel > 0 && z_superpixel <= (1 + ratio) * intervals[i]->near_m)
          evidence.push_back({t.current, residuals[i], 0.0});
        continue;
      }
      // Nor does one that lies off its superpixel's surface: where a superpixel straddles the mover's border (its
      // outline is found at a coarser scale), the track belongs to the other side.
      if (z_now > 0 && z_superpixel > 0 && std::fabs(z_now - z_superpixel) > ratio * std::min(z_now, z_superpixel))
        continue;
      evidence.push_back({t.current, residuals[i], out.epipolar_distance_px[i]});
    }
    const auto neighbours = superpixelNeighbours(segmentation.labels, diag.superpixels);
    const std::vector<RegionLabel> seeds =
        seedSuperpixels(segmentation.labels, segmentation.superpixels, neighbours, border, out.dynamic_cluster,
                        evidence, static_bar,
                        options_.epipolar.dynamic_threshold_px,
                        SeedOptions{seed_outside, options_.epipolar.min_dynamic_points});
    std::vector<bool> may_be_dynamic(diag.superpixels);
    for (int s = 0; s < diag.superpixels; ++s)
      may_be_dynamic[s] = out.dynamic_cluster[segmentation.superpixels[s].cluster] || seeds[s] == RegionLabel::kDynamic;
    const std::vector<RegionLabel> labels =
        growRegions(segmentation.superpixels, neighbours, seeds, may_be_dynamic, options_.superpixel.colour_scale,
                    options_.superpixel.depth_scale_m,
                    occlusionEdges(segmentation.labels, neighbours, in.depth, options_.reprojection.depth_edge_ratio));
    std::vector<uchar> dynamic_superpixel(diag.superpixels, 0);
    for (int s = 0; s < diag.superpixels; ++s) {
      dynamic_superpixel[s] = labels[s] == RegionLabel::kDynamic;
      diag.dynamic_superpixels += dynamic_superpixel[s];
    }
    for (int y = 0; y < out.mask.rows; ++y) {
      const int* sp = segmentation.labels.ptr<int>(y);
      uchar* m = out.mask.ptr<uchar>(y);
      for (int x = 0; x < out.mask.cols; ++x)
        if (dynamic_superpixel[sp[x]]) m[x] = 255;
    }
  } else {
    // The mask covers whole dynamic clusters, border blocks included (they only abstain from the decision).
    for (int y = 0; y < out.mask.rows; ++y) {
      const int* cm = out.cluster_map.ptr<int>(y);
      uchar* m = out.mask.ptr<uchar>(y);
      for (int x = 0; x < out.mask.cols; ++x)
        if (out.dynamic_cluster[cm[x]]) m[x] = 255;
    }
  }
  if (judge_prior) {
    std::vector<bool> keep(prior_count + 1, false);
    for (int r = 1; r <= prior_count; ++r) {
      keep[r] = prior_votes[r] >= min_votes;
      if (keep[r]) ++diag.dynamic_prior_regions;
    }
    for (int y = 0; y < out.mask.rows; ++y) {
      const int* pc = prior_components.ptr<int>(y);
      uchar* m = out.mask.ptr<uchar>(y);
      for (int x = 0; x < out.mask.cols; ++x)
        if (keep[pc[x]]) m[x] = 255;
    }
  }
  lap("decision");
  out.timings_ms.emplace_back("total", total.elapsedMs());
  return out;
}

}  // namespace amos::dynamic
