#include "amos/dynamic/dynamic_front_end.h"

#include <algorithm>
#include <opencv2/core.hpp>
#include <utility>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/dynamic/candidate_scoring.h"
#include "amos/dynamic/cluster_voting.h"
#include "amos/dynamic/depth_evidence.h"
#include "amos/dynamic/epipolar_evidence.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/mask_building.h"
#include "amos/dynamic/motion_hold.h"
#include "amos/dynamic/pose_confirmation.h"

namespace amos::dynamic {

DynamicFrontEnd::DynamicFrontEnd(const core::PinholeCamera& camera, const DynamicOptions& options)
    : camera_(camera), options_(options) {
  options_.check();
  if (options_.depth.enabled) depth_grid_ = DepthSampleGrid(camera_, options_.depth.sample_step_px);
  // Every 4th pixel: a superpixel of a few hundred pixels gets tens of samples for its median.
  if (options_.temporal.hold_frames > 0) hold_grid_ = DepthSampleGrid(camera_, 4);
}

namespace {

void checkInput(const FrontEndInput& in) {
  core::require(!in.gray.empty() && in.gray.type() == CV_8UC1, "DynamicFrontEnd: gray must be CV_8UC1");
  const cv::Size size = in.gray.size();
  core::require(in.bgr.type() == CV_8UC3 && in.bgr.size() == size, "DynamicFrontEnd: bgr must be CV_8UC3, gray's size");
  core::require(in.depth.type() == CV_32F && in.depth.size() == size,
                "DynamicFrontEnd: depth must be CV_32F metres, gray's size");
  core::require(in.prior_mask.empty() || (in.prior_mask.type() == CV_8UC1 && in.prior_mask.size() == size),
                "DynamicFrontEnd: prior_mask must be empty or CV_8UC1 of the image size");
  core::require(in.last_mask.empty() || (in.last_mask.type() == CV_8UC1 && in.last_mask.size() == size),
                "DynamicFrontEnd: last_mask must be empty or CV_8UC1 of the image size");
  core::require(in.baseline_depth.empty() || (in.baseline_depth.type() == CV_32F && in.baseline_depth.size() == size),
                "DynamicFrontEnd: baseline_depth must be empty or CV_32F of the image size");
  core::require(in.baseline_gray.empty() || (in.baseline_gray.type() == CV_8UC1 && in.baseline_gray.size() == size),
                "DynamicFrontEnd: baseline_gray must be empty or CV_8UC1 of the image size");
  if (!in.last_gray.empty()) {
    core::require(in.last_gray.type() == CV_8UC1 && in.last_gray.size() == size,
                  "DynamicFrontEnd: last_gray must be CV_8UC1 of the image size");
    core::require(in.last_depth.type() == CV_32F && in.last_depth.size() == size,
                  "DynamicFrontEnd: last_depth must be CV_32F of the image size");
  }
}

}  // namespace

FrontEndResult DynamicFrontEnd::process(const FrontEndInput& in) const {
  checkInput(in);
  core::Stopwatch total;
  FrontEndResult out;
  DynamicDiagnostics& diag = out.diagnostics;
  out.mask = cv::Mat(in.gray.size(), CV_8U, cv::Scalar(0));
  const DynamicMode mode = options_.mode;
  const bool use_prior = (mode == DynamicMode::kPrior || mode == DynamicMode::kFull) && !in.prior_mask.empty();
  const bool use_geometry = (mode == DynamicMode::kGeometry || mode == DynamicMode::kFull) && !in.last_gray.empty();

  // Prior regions (III-A): connected components of the (already dilated) segmentation mask. Unless they are judged
  // by their epipolar violators below, every one of them is dynamic.
  const PriorRegions prior = use_prior ? findPriorRegions(in.prior_mask) : PriorRegions{};
  diag.prior_regions = prior.count;
  const bool judge_prior = use_prior && use_geometry && options_.judge_prior_regions;
  if (use_prior && !judge_prior) {
    out.mask.setTo(255, in.prior_mask != 0);
    diag.dynamic_prior_regions = prior.count;
  }
  if (!use_geometry) {
    out.timings_ms.emplace_back("total", total.elapsedMs());
    return out;
  }
  diag.geometry_ran = true;
  core::Stopwatch stage;
  auto lap = [&](const char* name) {
    out.timings_ms.emplace_back(name, stage.elapsedMs());
    stage.restart();
  };

  // Stage 1a (III-B): superpixels and geometric clusters of the current frame; border blocks take no part in the
  // decisions (III-C).
  GeometricPartition computed;
  if (in.partition == nullptr)
    computed = computeGeometricPartition(in.bgr, in.depth, options_.superpixel, options_.cluster);
  const GeometricPartition& partition = in.partition ? *in.partition : computed;
  out.timings_ms.emplace_back("superpixels", partition.superpixel_ms);
  stage.restart();
  diag.superpixels = static_cast<int>(partition.segmentation.superpixels.size());
  diag.clusters = clusterCount(partition.segmentation);
  const DecisionRegions regions =
      options_.boundary.border_blocks
          ? findDecisionRegions(partition.segmentation, partition.cluster_map, options_.boundary.border_margin_px)
          : findEdgeDecisionRegions(partition.segmentation, partition.cluster_map, edgeBand());
  out.timings_ms.emplace_back("clusters", partition.cluster_ms + stage.elapsedMs());
  stage.restart();

  // Correspondences last -> current.
  out.tracks = in.tracks ? *in.tracks : trackCorners(in.last_gray, in.gray, options_.tracking);
  if (!options_.boundary.border_blocks) {
    // The per-track border rule at the other end: the edge band of the decision map takes the tracks that end near
    // the image edge out of the decisions; a track that started there had its LK template cut by the frame (a
    // camera turning brings such points inwards within a frame) and goes too.
    const float band = static_cast<float>(edgeBand());
    const float max_x = static_cast<float>(in.gray.cols - 1) - band, max_y = static_cast<float>(in.gray.rows - 1) - band;
    out.tracks.erase(std::remove_if(out.tracks.begin(), out.tracks.end(),
                                    [&](const PointTrack& t) {
                                      return t.last.x < band || t.last.y < band || t.last.x > max_x || t.last.y > max_y;
                                    }),
                     out.tracks.end());
  }
  diag.tracks = static_cast<int>(out.tracks.size());
  lap("tracking");

  // Stage 1b (III-C, Eq. 5-6): the potential motion regions from the reprojection errors under the initial pose,
  // and every cluster judged again under the pose refitted without them.
  CandidateScoring candidates =
      scoreCandidates(out.tracks, in, regions.decision_map, diag.clusters, prior, camera_, options_, diag);
  PoseConfirmation confirmation = confirmUnderRefittedPose(out.tracks, candidates, in.T_cw_last, in.T_cw_initial,
                                                           camera_, options_.reprojection, diag);
  lap("reprojection");

  // Stage 2 (III-C, Eq. 7-8): fundamental matrix on the undistorted tracks outside the potential motion regions,
  // epipolar distance of every track.
  EpipolarEvidence epipolar =
      fitEpipolarEvidence(out.tracks, confirmation.fit_tracks, camera_, options_.epipolar, diag);
  lap("epipolar");

  // Depth evidence (depth_evidence.h): superpixels whose depth moved under the judged pose, for movers that carry
  // too few tracks to be scored.
  DepthEvidence depth;
  std::vector<bool> depth_moving;
  if (options_.depth.enabled) {
    depth = frameDepthEvidence(in.depth, confirmation.refit.T_cw, in.last_depth, in.T_cw_last, in.baseline_depth,
                               in.T_cw_baseline, camera_, depth_grid_, partition.segmentation,
                               options_.reprojection.depth_edge_ratio, options_.depth);
    for (const SuperpixelDepth& sp : depth.superpixels) depth_moving.push_back(sp.moving);
    diag.depth_moving_superpixels = depth.moving_superpixels;
    lap("depth");
  }

  // Long-baseline tracks (baseline_tracks.h): the tracked points against the frame Dynamic.Depth.baselineFrames
  // back, for movers too slow for one frame.
  BaselineMotion baseline;
  std::vector<bool> baseline_moving;
  std::vector<int> baseline_points;  // per superpixel, for growOverSurface
  SurfaceSeeds surface_seeds;         // the rigid movers' (Dynamic.RigidMovers.growOverSurface)
  if (options_.baseline_tracks.enabled && !in.baseline_gray.empty()) {
    std::vector<cv::Point2f> points;
    points.reserve(out.tracks.size());
    for (const PointTrack& t : out.tracks) points.push_back(t.current);
    // The pipeline's stage A builds the pyramids; otherwise they are built here.
    const bool have_pyramids = !in.pyramid.empty() && !in.baseline_pyramid.empty();
    const ImagePyramid pyramid = have_pyramids ? in.pyramid : buildPyramid(in.gray, options_.tracking);
    const ImagePyramid baseline_pyramid =
        have_pyramids ? in.baseline_pyramid : buildPyramid(in.baseline_gray, options_.tracking);
    baseline = baselineMotion(points, pyramid, in.depth, confirmation.refit.T_cw, baseline_pyramid, in.T_cw_baseline,
                              camera_, options_.tracking, options_.reprojection, options_.baseline_tracks);
    // The pipeline's stage A computes the graph with the partition; otherwise it is computed here only when the
    // vote pools over it or moving points are densified (mask building computes its own when it needs one).
    const int superpixels = static_cast<int>(partition.segmentation.superpixels.size());
    std::optional<SuperpixelGraph> own_graph;
    const bool densify = options_.baseline_tracks.densify_points > 0 && baseline.ok && baseline.moving_points > 0;
    if (!partition.graph && (options_.baseline_tracks.pool_neighbours || densify))
      own_graph = superpixelGraph(partition.segmentation, in.depth, options_.reprojection.depth_edge_ratio);
    const SuperpixelGraph* graph = partition.graph ? &*partition.graph : own_graph ? &*own_graph : nullptr;
    diag.baseline_dense_points =
        densifyBaselineMotion(baseline, pyramid, in.depth, confirmation.refit.T_cw, baseline_pyramid,
                              in.baseline_depth, in.T_cw_baseline, camera_, partition.segmentation.labels, superpixels,
                              graph, options_.tracking, options_.reprojection, options_.baseline_tracks);
    diag.baseline_points = static_cast<int>(baseline.points.size());
    diag.baseline_moving_points = baseline.moving_points;
    baseline_moving = baselineMovingSuperpixels(baseline, partition.segmentation.labels, superpixels,
                                                options_.baseline_tracks, graph);
    if (options_.baseline_tracks.grow_over_surface || options_.rigid_movers.grow_over_surface)
      baseline_points = baselinePointsPerSuperpixel(baseline, partition.segmentation.labels, superpixels);
    lap("baseline_tracks");
    // Rigid movers (rigid_movers.h): the moving points' rigid motions, and the superpixels that follow one.
    if (options_.rigid_movers.enabled) {
      const RigidDepthInput depth_input{depth_grid_, options_.depth, options_.reprojection.depth_edge_ratio};
      const RigidMoverVerdict rigid = rigidMoverSuperpixels(
          baseline, in.gray, in.depth, confirmation.refit.T_cw, in.baseline_gray, in.baseline_depth,
          in.T_cw_baseline, camera_, partition.segmentation.labels, superpixels, options_.reprojection,
          options_.rigid_movers, options_.depth.enabled ? &depth_input : nullptr);
      diag.rigid_movers = static_cast<int>(rigid.movers.size());
      diag.rigid_superpixels = rigid.moving_superpixels;
      for (std::size_t s = 0; s < rigid.moving.size() && s < baseline_moving.size(); ++s)
        baseline_moving[s] = baseline_moving[s] || rigid.moving[s];
      if (options_.rigid_movers.grow_over_surface) {
        surface_seeds.seeds = rigid.moving;
        surface_seeds.within = superpixelsNearMovers(partition.segmentation.superpixels, rigid.movers,
                                                     options_.rigid_movers.region_reach_px);
      }
      lap("rigid_movers");
    }
  }

  // Decision: the epipolar violators vote for clusters and judged prior regions, then the mask follows the dynamic
  // clusters per superpixel (or covers them whole) and the prior regions that stay.
  const PriorRegions judged_prior = judge_prior ? prior : PriorRegions{};
  ClusterVoting voting = voteClusters(epipolar.violators, regions.decision_map, candidates.cluster_scores,
                                      confirmation.confirmed, judged_prior, options_, diag);
  if (options_.depth.enabled) {
    diag.depth_dynamic_clusters =
        addDepthMovingClusters(depth, partition.segmentation, candidates.cluster_scores,
                               options_.reprojection.min_points_per_cluster, options_.depth, voting.dynamic_cluster);
    diag.dynamic_clusters += diag.depth_dynamic_clusters;
  }
  if (!baseline_moving.empty()) {
    const std::vector<bool> moved = baselineMovingClusters(
        baseline, regions.decision_map, static_cast<int>(voting.dynamic_cluster.size()), options_.baseline_tracks);
    for (std::size_t c = 0; c < moved.size(); ++c)
      if (moved[c] && !voting.dynamic_cluster[c]) {
        voting.dynamic_cluster[c] = true;
        ++diag.baseline_dynamic_clusters;
        ++diag.dynamic_clusters;
      }
  }
  if (options_.boundary.grow_from_confirmed > 0 && confirmation.refit.ok) {
    // Clusters that move well beyond the confirmation threshold (boundary_assignment.h, growFromConfirmed).
    const double bar = options_.boundary.grow_from_confirmed * confirmation.static_bar_px;
    surface_seeds.strong_clusters.assign(voting.dynamic_cluster.size(), false);
    for (std::size_t c = 0; c < voting.dynamic_cluster.size() && c < confirmation.confirm_scores.size(); ++c)
      surface_seeds.strong_clusters[c] = voting.dynamic_cluster[c] && confirmation.confirmed[c] &&
                                         confirmation.confirm_scores[c].equivalent_px >= bar;
    for (const ClusterScore& score : candidates.cluster_scores)
      surface_seeds.unscored_clusters.push_back(score.points < options_.reprojection.min_points_per_cluster);
  }
  const DynamicMask mask = buildDynamicMask(in, out.tracks, partition, regions, candidates, confirmation, epipolar,
                                            voting, judged_prior, depth_moving, options_, diag, baseline_moving,
                                            baseline_points, surface_seeds);
  cv::bitwise_or(out.mask, mask.mask, out.mask);
  lap("decision");

  // Temporal hold (motion_hold.h): what this frame's tests found moving, carried over the frames where a mover
  // that slows down falls below them.
  if (options_.temporal.hold_frames > 0) {
    MotionHoldInput hold_in;
    hold_in.evidence_mask = &mask.mask;
    hold_in.labels = &partition.segmentation.labels;
    hold_in.count = static_cast<int>(partition.segmentation.superpixels.size());
    hold_in.depth = &in.depth;
    hold_in.T_cw = confirmation.refit.T_cw;
    hold_in.last_score = &in.last_hold_score;
    hold_in.last_depth = &in.last_depth;
    hold_in.T_cw_last = in.T_cw_last;
    // Static evidence at this frame's noise level ends a hold (motion_hold.h).
    std::vector<bool> seen_static(static_cast<std::size_t>(hold_in.count), false);
    if (confirmation.refit.ok) {
      seen_static = stillSuperpixels(out.tracks, residualNorms(confirmation.residuals), partition.segmentation.labels,
                                     hold_in.count, confirmation.refit.sigma_px);
    }
    if (baseline.ok) {
      const std::vector<bool> stayed = baselineStaticSuperpixels(baseline, partition.segmentation.labels,
                                                                 hold_in.count, options_.baseline_tracks);
      for (std::size_t s = 0; s < stayed.size() && s < seen_static.size(); ++s)
        seen_static[s] = seen_static[s] || stayed[s];
    }
    hold_in.seen_static = &seen_static;
    MotionHold hold =
        holdMotion(hold_in, camera_, hold_grid_, options_.depth, options_.temporal.hold_frames,
                   options_.temporal.hold_min_frames);
    diag.held_superpixels = hold.held_superpixels;
    if (hold.held_superpixels > 0) markLabelledPixels(partition.segmentation.labels, hold.held, out.mask);
    out.hold_score = std::move(hold.score);
    lap("hold");
  }

  out.superpixel_labels = partition.segmentation.labels;
  out.cluster_map = partition.cluster_map;
  out.cluster_scores = std::move(candidates.cluster_scores);
  out.reprojection_error_px = std::move(candidates.errors_px);
  out.confirm_scores = std::move(confirmation.confirm_scores);
  out.judged_error_px = residualNorms(confirmation.residuals);
  out.T_cw_judged = confirmation.refit.T_cw;
  out.dynamic_cluster = std::move(voting.dynamic_cluster);
  out.epipolar_distance_px = std::move(epipolar.distance_px);
  out.baseline_bar_px = baseline.bar_px;
  out.baseline_points = std::move(baseline.points);
  out.timings_ms.emplace_back("total", total.elapsedMs());
  return out;
}

}  // namespace amos::dynamic
