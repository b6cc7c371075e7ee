#include "amos/dynamic/dynamic_front_end.h"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"

namespace amos::dynamic {

DynamicFrontEnd::DynamicFrontEnd(const core::PinholeCamera& camera, const DynamicOptions& options)
    : camera_(camera), options_(options) {
  options_.check();
}

namespace {

int labelAt(const cv::Mat& map, cv::Point2f p) {
  const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
  if (x < 0 || y < 0 || x >= map.cols || y >= map.rows) return -1;
  return map.at<int>(y, x);
}

void checkInput(const DynamicFrameInput& in) {
  core::require(!in.gray.empty() && in.gray.type() == CV_8UC1, "DynamicFrontEnd: gray must be CV_8UC1");
  const cv::Size size = in.gray.size();
  core::require(in.bgr.type() == CV_8UC3 && in.bgr.size() == size, "DynamicFrontEnd: bgr must be CV_8UC3, gray's size");
  core::require(in.depth.type() == CV_32F && in.depth.size() == size,
                "DynamicFrontEnd: depth must be CV_32F metres, gray's size");
  core::require(in.prior_mask.empty() || (in.prior_mask.type() == CV_8UC1 && in.prior_mask.size() == size),
                "DynamicFrontEnd: prior_mask must be empty or CV_8UC1 of the image size");
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

  // Prior regions: connected components of the (already dilated) segmentation mask.
  cv::Mat prior_components;
  int prior_count = 0;
  if (use_prior) {
    prior_count = cv::connectedComponents(in.prior_mask != 0, prior_components, 8, CV_32S) - 1;
    out.diagnostics.prior_regions = prior_count;
  }
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
  SuperpixelSegmentation segmentation = computeDepthSlic(in.bgr, in.depth, options_.superpixel);
  lap("superpixels");
  out.cluster_map = clusterSuperpixels(segmentation, options_.cluster);
  const int num_clusters = clusterCount(segmentation);
  diag.superpixels = static_cast<int>(segmentation.superpixels.size());
  diag.clusters = num_clusters;
  // Border blocks take no part in the decisions (III-C).
  const std::vector<bool> border =
      borderSuperpixels(segmentation.labels, diag.superpixels, options_.boundary.border_margin_px);
  const cv::Mat decision_map = decisionClusterMap(out.cluster_map, segmentation.labels, border);
  lap("clusters");

  // Correspondences last -> current.
  out.tracks = in.tracks ? *in.tracks : trackCorners(in.last_gray, in.gray, options_.tracking);
  diag.tracks = static_cast<int>(out.tracks.size());
  lap("tracking");

  // Stage 1b (III-C, Eq. 5-6): cluster scores from reprojection errors under the initial pose.
  const auto points_w = backProjectTracks(out.tracks, in.last_depth, in.T_cw_last, camera_, options_.reprojection);
  out.reprojection_error_px = reprojectionErrors(out.tracks, points_w, in.T_cw_initial, camera_);
  const auto& errors = out.reprojection_error_px;
  std::vector<int> cluster_of_track(out.tracks.size());
  for (std::size_t i = 0; i < out.tracks.size(); ++i) {
    cluster_of_track[i] = labelAt(decision_map, out.tracks[i].current);
    if (errors[i]) ++diag.tracks_with_depth;
  }
  out.cluster_scores = scoreClusters(errors, cluster_of_track, num_clusters, options_.reprojection);
  std::vector<double> cluster_error(num_clusters);
  for (int c = 0; c < num_clusters; ++c) {
    cluster_error[c] = out.cluster_scores[c].mean_rho;
    if (out.cluster_scores[c].candidate) ++diag.candidate_clusters;
  }
  lap("reprojection");

  // Stage 2 (III-C, Eq. 7-8): fundamental matrix on undistorted tracks, epipolar distance of every track.
  std::vector<cv::Point2f> last_raw, current_raw;
  for (const PointTrack& t : out.tracks) last_raw.push_back(t.last), current_raw.push_back(t.current);
  const std::vector<cv::Point2f> last_u = camera_.undistort(last_raw), current_u = camera_.undistort(current_raw);
  // F is fitted on the tracks outside the potential motion regions (candidate clusters, prior regions): a rigid
  // moving object holding many tracks would otherwise pull F towards its own motion whenever the static scene
  // has little parallax (small baseline, one dominant plane), and then it would satisfy the epipolar test.
  // With too few such tracks (e.g. every cluster a candidate after a bad initial pose) all tracks are used.
  std::vector<cv::Point2f> fit_last, fit_current;
  for (std::size_t i = 0; i < out.tracks.size(); ++i) {
    const int c = cluster_of_track[i];
    if (c >= 0 && out.cluster_scores[c].candidate) continue;
    if (use_prior && labelAt(prior_components, out.tracks[i].current) > 0) continue;
    fit_last.push_back(last_u[i]);
    fit_current.push_back(current_u[i]);
  }
  if (static_cast<int>(fit_last.size()) < options_.epipolar.min_fit_points) fit_last = last_u, fit_current = current_u;
  diag.f_fit_points = static_cast<int>(fit_last.size());
  const FundamentalFit fit = fitFundamental(fit_last, fit_current, options_.epipolar);
  diag.fundamental_ok = fit.ok;
  diag.f_ransac_inliers = fit.ransac_inliers;
  diag.f_refit_points = fit.refit_points;
  diag.f_final_inliers = fit.final_inliers;
  out.epipolar_distance_px.assign(out.tracks.size(), std::numeric_limits<double>::infinity());
  if (fit.ok) {
    for (std::size_t i = 0; i < out.tracks.size(); ++i)
      out.epipolar_distance_px[i] =
          epipolarDistance(fit.F, {last_u[i].x, last_u[i].y}, {current_u[i].x, current_u[i].y});
  }
  lap("epipolar");

  // Decision: each epipolar violator votes for the cluster it belongs to after boundary reassignment and for
  // the prior region it lies in; a candidate region with enough votes is dynamic. Without F nothing is judged.
  std::vector<int> cluster_votes(num_clusters, 0), prior_votes(prior_count + 1, 0);
  if (fit.ok) {
    for (std::size_t i = 0; i < out.tracks.size(); ++i) {
      if (!(out.epipolar_distance_px[i] > options_.epipolar.dynamic_threshold_px)) continue;
      ++diag.dynamic_points;
      const cv::Point2f p = out.tracks[i].current;
      if (judge_prior) {
        const int region = labelAt(prior_components, p);
        if (region > 0) ++prior_votes[region];
      }
      if (labelAt(decision_map, p) < 0) continue;  // in a border block
      const int c = assignToNeighbourCluster(p, decision_map, cluster_error, options_.boundary.search_radius_px);
      if (c >= 0) ++cluster_votes[c];
    }
  }
  const int min_votes = options_.epipolar.min_dynamic_points;
  out.dynamic_cluster.assign(num_clusters, false);
  for (int c = 0; c < num_clusters; ++c) {
    out.dynamic_cluster[c] = out.cluster_scores[c].candidate && cluster_votes[c] >= min_votes;
    if (out.dynamic_cluster[c]) ++diag.dynamic_clusters;
  }
  // The mask covers whole dynamic clusters, border blocks included (they only abstain from the decision).
  for (int y = 0; y < out.mask.rows; ++y) {
    const int* cm = out.cluster_map.ptr<int>(y);
    uchar* m = out.mask.ptr<uchar>(y);
    for (int x = 0; x < out.mask.cols; ++x)
      if (out.dynamic_cluster[cm[x]]) m[x] = 255;
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
