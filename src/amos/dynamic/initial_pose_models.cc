#include "amos/dynamic/initial_pose_models.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/dynamic/frame_regions.h"

namespace amos::dynamic {

void InitialPoseOptions::check() const {
  core::requirePositive(inlier_threshold_px, "inlier_threshold_px");
  core::requireAtLeast(keyframe_max_points, "keyframe_max_points", 0);
  pnp.check();
}

void PoseCorrespondences::append(const PoseCorrespondences& other) {
  points_w.insert(points_w.end(), other.points_w.begin(), other.points_w.end());
  pixels.insert(pixels.end(), other.pixels.begin(), other.pixels.end());
}

std::string toString(PoseModel model) {
  switch (model) {
    case PoseModel::kReferenceKeyframe:
      return "reference_keyframe";
    case PoseModel::kLastFrame:
      return "last_frame";
    case PoseModel::kConstantVelocity:
      return "constant_velocity";
  }
  return "unknown";
}

std::vector<std::size_t> everyKth(const std::vector<std::size_t>& items, int max_count) {
  if (max_count <= 0 || items.size() <= static_cast<std::size_t>(max_count)) return items;
  const std::size_t max = static_cast<std::size_t>(max_count);
  const std::size_t stride = (items.size() + max - 1) / max;
  std::vector<std::size_t> out;
  out.reserve(max);
  for (std::size_t k = 0; k < items.size(); k += stride) out.push_back(items[k]);
  return out;
}

PoseCorrespondences keyframeCorrespondences(const FramePairPyramids& keyframe_to_current,
                                            const std::vector<cv::Point2f>& keyframe_pixels,
                                            const std::vector<Eigen::Vector3d>& keyframe_points_w,
                                            const core::PinholeCamera& camera, const CornerTrackingOptions& tracking) {
  core::require(keyframe_pixels.size() == keyframe_points_w.size(),
                "keyframeCorrespondences: pixels and world points differ in number");
  const std::vector<PointTrack> tracks = trackPoints(keyframe_to_current, keyframe_pixels, tracking);
  std::vector<cv::Point2f> raw;
  raw.reserve(tracks.size());
  for (const PointTrack& t : tracks) raw.push_back(t.current);
  const std::vector<cv::Point2f> undistorted = camera.undistort(raw);
  PoseCorrespondences out;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    out.points_w.push_back(keyframe_points_w[tracks[i].source_index]);
    out.pixels.emplace_back(undistorted[i].x, undistorted[i].y);
  }
  return out;
}

PoseCorrespondences lastFrameCorrespondences(const std::vector<PointTrack>& tracks,
                                             const std::vector<std::optional<Eigen::Vector3d>>& points_w,
                                             const core::PinholeCamera& camera) {
  core::require(tracks.size() == points_w.size(), "lastFrameCorrespondences: tracks and points differ in number");
  std::vector<cv::Point2f> raw;
  raw.reserve(tracks.size());
  for (const PointTrack& t : tracks) raw.push_back(t.current);
  const std::vector<cv::Point2f> undistorted = camera.undistort(raw);
  PoseCorrespondences out;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!points_w[i]) continue;
    out.points_w.push_back(*points_w[i]);
    out.pixels.emplace_back(undistorted[i].x, undistorted[i].y);
  }
  return out;
}

core::SE3 velocityFrom(const core::SE3& T_cw_last, const core::SE3& T_cw_before_last) {
  return T_cw_last * T_cw_before_last.inverse();
}

core::SE3 constantVelocityPose(const core::SE3& T_cw_last, const core::SE3& velocity) { return velocity * T_cw_last; }

namespace {

constexpr int kCoverageCols = 8, kCoverageRows = 6;  // cells of ~80 x 80 px at 640 x 480

// Indices of the correspondences whose reprojection error under T_cw is below threshold_px (never those behind the
// camera): what countInliers counts and countInlierCells spreads over the grid.
std::vector<int> inlierIndices(const core::SE3& T_cw, const PoseCorrespondences& correspondences,
                               const core::PinholeCamera& camera, double threshold_px) {
  const double t2 = threshold_px * threshold_px;
  std::vector<int> inliers;
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    const Eigen::Vector3d p_c = T_cw * correspondences.points_w[i];
    if (p_c.z() > 1e-6 && (camera.project(p_c) - correspondences.pixels[i]).squaredNorm() < t2)
      inliers.push_back(static_cast<int>(i));
  }
  return inliers;
}

}  // namespace

int countInliers(const core::SE3& T_cw, const PoseCorrespondences& correspondences, const core::PinholeCamera& camera,
                 double threshold_px) {
  return static_cast<int>(inlierIndices(T_cw, correspondences, camera, threshold_px).size());
}

int countInlierCells(const core::SE3& T_cw, const PoseCorrespondences& correspondences,
                     const core::PinholeCamera& camera, double threshold_px, int cols, int rows) {
  return geometry::countCoveredCells(correspondences.pixels, inlierIndices(T_cw, correspondences, camera, threshold_px),
                                     camera.intrinsics().width, camera.intrinsics().height, cols, rows);
}

std::vector<PointTrack> tracksOffMask(const std::vector<PointTrack>& tracks, const cv::Mat& last_mask) {
  if (last_mask.empty()) return tracks;
  std::vector<PointTrack> kept;
  kept.reserve(tracks.size());
  for (const PointTrack& t : tracks)
    if (!maskAt(last_mask, t.last)) kept.push_back(t);
  return kept;
}

PoseCandidate poseFromCorrespondences(PoseModel model, const PoseCorrespondences& correspondences,
                                      const core::PinholeCamera& camera, const InitialPoseOptions& options) {
  PoseCandidate candidate;
  candidate.model = model;
  if (static_cast<int>(correspondences.size()) < options.pnp.min_inliers) return candidate;
  geometry::PnpRansacOptions ransac = options.pnp;
  if (options.select_by_coverage) ransac.coverage_cols = kCoverageCols, ransac.coverage_rows = kCoverageRows;
  const geometry::PnpResult pnp =
      geometry::solvePnpRansac(correspondences.points_w, correspondences.pixels, camera, ransac);
  candidate.valid = pnp.success;
  candidate.T_cw = pnp.T_cw;
  candidate.own_inliers = static_cast<int>(pnp.inliers.size());
  return candidate;
}

InitialPoseResult selectInitialPose(std::vector<PoseCandidate> candidates, const PoseCorrespondences& common,
                                    const core::PinholeCamera& camera, const InitialPoseOptions& options) {
  options.check();
  InitialPoseResult result;
  result.common_size = static_cast<int>(common.size());
  int best = -1;  // the most common inliers (ties: model order)
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    PoseCandidate& c = candidates[i];
    if (!c.valid) continue;
    const std::vector<int> inliers = inlierIndices(c.T_cw, common, camera, options.inlier_threshold_px);
    c.common_inliers = static_cast<int>(inliers.size());
    if (options.select_by_coverage)
      c.common_cells = geometry::countCoveredCells(common.pixels, inliers, camera.intrinsics().width,
                                                   camera.intrinsics().height, kCoverageCols, kCoverageRows);
    if (best < 0 || c.common_inliers > candidates[best].common_inliers) best = static_cast<int>(i);
  }
  if (options.select_by_coverage && best >= 0) {
    // Of the candidates with at least coverage_min_support times the most inliers, the widest (as inside the PnP
    // RANSACs, geometry::PnpRansacOptions::coverage_min_support).
    const double floor = options.pnp.coverage_min_support * candidates[best].common_inliers;
    int widest = -1;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const PoseCandidate& c = candidates[i];
      if (!c.valid || c.common_inliers < floor) continue;
      const PoseCandidate* w = widest < 0 ? nullptr : &candidates[widest];
      if (!w || c.common_cells > w->common_cells ||
          (c.common_cells == w->common_cells && c.common_inliers > w->common_inliers))
        widest = static_cast<int>(i);
    }
    best = widest;
  }
  if (best >= 0) {
    result.ok = true;
    result.T_cw = candidates[best].T_cw;
    result.model = candidates[best].model;
  }
  result.candidates = std::move(candidates);
  return result;
}

InitialPoseResult estimateInitialPose(const PoseCorrespondences& keyframe, const PoseCorrespondences& last_frame,
                                      const core::SE3& T_cw_last, const std::optional<core::SE3>& velocity,
                                      const core::PinholeCamera& camera, const InitialPoseOptions& options) {
  options.check();
  std::vector<PoseCandidate> candidates;
  candidates.push_back(poseFromCorrespondences(PoseModel::kReferenceKeyframe, keyframe, camera, options));
  candidates.push_back(poseFromCorrespondences(PoseModel::kLastFrame, last_frame, camera, options));
  PoseCandidate cv_candidate;
  cv_candidate.model = PoseModel::kConstantVelocity;
  cv_candidate.valid = velocity.has_value();
  if (velocity) cv_candidate.T_cw = constantVelocityPose(T_cw_last, *velocity);
  candidates.push_back(cv_candidate);
  PoseCorrespondences common = keyframe;
  common.append(last_frame);
  return selectInitialPose(std::move(candidates), common, camera, options);
}

}  // namespace amos::dynamic
