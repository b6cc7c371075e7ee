#include "amos/dynamic/reprojection_scoring.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/dynamic/robust_scale.h"

namespace amos::dynamic {

void ReprojectionOptions::check() const {
  core::requirePositive(cauchy_scale_px, "cauchy_scale_px");
  core::requirePositive(candidate_threshold_px, "candidate_threshold_px");
  core::requireAtLeast(min_points_per_cluster, "min_points_per_cluster", 1);
  core::requirePositive(max_depth_m, "max_depth_m");
  core::requirePositive(depth_edge_ratio, "depth_edge_ratio");
  core::requireAtLeast(refit_min_points, "refit_min_points", 6);
  core::requirePositive(confirm_threshold_px, "confirm_threshold_px");
  core::requireOption(std::isfinite(confirm_sigmas) && confirm_sigmas >= 0,
                      core::option(confirm_sigmas, "confirm_sigmas"),
                      fmt::format("must be >= 0, got {}", confirm_sigmas));
}

double cauchyRho(double squared_error, double scale) {
  const double c2 = scale * scale;
  return c2 * std::log1p(squared_error / c2);
}

double cauchyEquivalentError(double mean_rho, double scale) {
  const double c2 = scale * scale;
  return std::sqrt(std::max(0.0, c2 * std::expm1(mean_rho / c2)));
}

namespace {
// A Shi-Tomasi corner (3x3 gradient block, 3x3 Sobel) is shaped by the pixels within 2 px of it: when a depth
// edge lies that close, the corner may move with the other side of the edge than the depth read at its centre.
constexpr int kEdgeRadius = 2;
}  // namespace

std::vector<std::optional<Eigen::Vector3d>> backProjectTracks(const std::vector<PointTrack>& tracks,
                                                              const cv::Mat& last_depth, const core::SE3& T_cw_last,
                                                              const core::PinholeCamera& camera,
                                                              const ReprojectionOptions& options) {
  options.check();
  core::require(last_depth.type() == CV_32F, "backProjectTracks: depth must be CV_32F metres");
  std::vector<cv::Point2f> raw;
  raw.reserve(tracks.size());
  for (const PointTrack& t : tracks) raw.push_back(t.last);
  const std::vector<cv::Point2f> undistorted = camera.undistort(raw);
  const core::SE3 T_wl = T_cw_last.inverse();
  std::vector<std::optional<Eigen::Vector3d>> points(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    // Depth is registered to the raw image: read it at the raw pixel.
    const int u = static_cast<int>(std::lround(raw[i].x)), v = static_cast<int>(std::lround(raw[i].y));
    if (u < kEdgeRadius || v < kEdgeRadius || u >= last_depth.cols - kEdgeRadius || v >= last_depth.rows - kEdgeRadius)
      continue;
    const float z = last_depth.at<float>(v, u);
    if (!(z > 0.f) || z > options.max_depth_m) continue;
    float lo = z, hi = z;
    bool hole = false;
    for (int dv = -kEdgeRadius; dv <= kEdgeRadius; ++dv)
      for (int du = -kEdgeRadius; du <= kEdgeRadius; ++du) {
        const float zn = last_depth.at<float>(v + dv, u + du);
        if (!(zn > 0.f) || !std::isfinite(zn)) hole = true;
        lo = std::min(lo, zn), hi = std::max(hi, zn);
      }
    if (hole || hi - lo > options.depth_edge_ratio * z) continue;
    // Eq. 6: P = T_wl [Z (u - cx) / fx, Z (v - cy) / fy, Z]^T.
    points[i] = T_wl * camera.backProject(undistorted[i].x, undistorted[i].y, z);
  }
  return points;
}

std::vector<std::optional<Eigen::Vector2d>> reprojectionResiduals(
    const std::vector<PointTrack>& tracks, const std::vector<std::optional<Eigen::Vector3d>>& points_w,
    const core::SE3& T_cw_current, const core::PinholeCamera& camera) {
  core::require(tracks.size() == points_w.size(), "reprojectionResiduals: tracks and points differ in number");
  std::vector<cv::Point2f> raw;
  raw.reserve(tracks.size());
  for (const PointTrack& t : tracks) raw.push_back(t.current);
  const std::vector<cv::Point2f> undistorted = camera.undistort(raw);
  std::vector<std::optional<Eigen::Vector2d>> residuals(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!points_w[i]) continue;
    const Eigen::Vector3d p_c = T_cw_current * *points_w[i];
    if (p_c.z() <= 1e-6) continue;
    residuals[i] = Eigen::Vector2d(undistorted[i].x, undistorted[i].y) - camera.project(p_c);
  }
  return residuals;
}

std::vector<std::optional<double>> residualNorms(const std::vector<std::optional<Eigen::Vector2d>>& residuals) {
  std::vector<std::optional<double>> errors(residuals.size());
  for (std::size_t i = 0; i < residuals.size(); ++i)
    if (residuals[i]) errors[i] = residuals[i]->norm();
  return errors;
}

std::vector<std::optional<double>> reprojectionErrors(const std::vector<PointTrack>& tracks,
                                                      const std::vector<std::optional<Eigen::Vector3d>>& points_w,
                                                      const core::SE3& T_cw_current, const core::PinholeCamera& camera) {
  return residualNorms(reprojectionResiduals(tracks, points_w, T_cw_current, camera));
}

std::vector<std::optional<DepthInterval>> trackDepthIntervals(const std::vector<PointTrack>& tracks,
                                                              const cv::Mat& last_depth, int radius_px,
                                                              const ReprojectionOptions& options) {
  core::require(last_depth.type() == CV_32F, "trackDepthIntervals: depth must be CV_32F metres");
  core::require(radius_px >= 0, "trackDepthIntervals: negative radius");
  std::vector<std::optional<DepthInterval>> intervals(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const int u = static_cast<int>(std::lround(tracks[i].last.x)), v = static_cast<int>(std::lround(tracks[i].last.y));
    if (u < 0 || v < 0 || u >= last_depth.cols || v >= last_depth.rows) continue;
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    bool open = false;
    for (int y = std::max(0, v - radius_px); y <= std::min(last_depth.rows - 1, v + radius_px); ++y) {
      const float* row = last_depth.ptr<float>(y);
      for (int x = std::max(0, u - radius_px); x <= std::min(last_depth.cols - 1, u + radius_px); ++x) {
        const float z = row[x];
        if (!(z > 0.f) || !std::isfinite(z) || z > options.max_depth_m) {
          open = true;
          continue;
        }
        lo = std::min(lo, static_cast<double>(z)), hi = std::max(hi, static_cast<double>(z));
      }
    }
    if (hi <= 0) continue;
    intervals[i] = DepthInterval{lo, open ? std::numeric_limits<double>::infinity() : hi};
  }
  return intervals;
}

std::vector<std::optional<Eigen::Vector2d>> intervalResiduals(const std::vector<PointTrack>& tracks,
                                                              const std::vector<std::optional<DepthInterval>>& intervals,
                                                              const core::SE3& T_cw_last, const core::SE3& T_cw_current,
                                                              const core::PinholeCamera& camera) {
  core::require(tracks.size() == intervals.size(), "intervalResiduals: tracks and intervals differ in number");
  std::vector<cv::Point2f> last_raw, current_raw;
  last_raw.reserve(tracks.size()), current_raw.reserve(tracks.size());
  for (const PointTrack& t : tracks) last_raw.push_back(t.last), current_raw.push_back(t.current);
  const std::vector<cv::Point2f> last_u = camera.undistort(last_raw), current_u = camera.undistort(current_raw);
  const core::SE3 T_cl = T_cw_current * T_cw_last.inverse();
  std::vector<std::optional<Eigen::Vector2d>> residuals(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!intervals[i]) continue;
    // The ray X(z) = z R d + t in the current camera; its image is a segment between the ends' projections.
    const Eigen::Vector3d d = camera.backProject(last_u[i].x, last_u[i].y, 1.0);
    const Eigen::Vector3d Rd = T_cl.rotation() * d, t = T_cl.translation();
    const Eigen::Vector3d near_c = intervals[i]->near_m * Rd + t;
    if (near_c.z() <= 1e-6) continue;
    const Eigen::Vector2d a = camera.project(near_c);
    Eigen::Vector2d b = a;
    if (std::isfinite(intervals[i]->far_m)) {
      const Eigen::Vector3d far_c = intervals[i]->far_m * Rd + t;
      if (far_c.z() > 1e-6) b = camera.project(far_c);
    } else if (Rd.z() > 1e-9) {
      b = camera.project(Rd);  // the vanishing point of the ray
    }
    const Eigen::Vector2d p(current_u[i].x, current_u[i].y);
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    residuals[i] = p - (a + s * ab);
  }
  return residuals;
}

double confirmThreshold(const PoseRefit& refit, const ReprojectionOptions& options) {
  return std::max(options.confirm_threshold_px, options.confirm_sigmas * refit.sigma_px);
}

PoseRefit refitPose(const std::vector<PointTrack>& tracks, const std::vector<std::optional<Eigen::Vector3d>>& points_w,
                    const std::vector<bool>& use, const core::SE3& T_cw_initial, const core::PinholeCamera& camera,
                    const ReprojectionOptions& options) {
  options.check();
  core::require(tracks.size() == points_w.size() && tracks.size() == use.size(),
                "refitPose: tracks, points and flags differ in number");
  std::vector<cv::Point2f> raw;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!use[i] || !points_w[i]) continue;
    raw.push_back(tracks[i].current);
    index.push_back(i);
  }
  PoseRefit refit;
  refit.T_cw = T_cw_initial;
  refit.points = static_cast<int>(index.size());
  if (refit.points < options.refit_min_points) return refit;
  const std::vector<cv::Point2f> undistorted = camera.undistort(raw);
  std::vector<geometry::PoseObservation> observations(index.size());
  for (std::size_t k = 0; k < index.size(); ++k) {
    observations[k].point_w = *points_w[index[k]];
    observations[k].pixel = {undistorted[k].x, undistorted[k].y};
  }
  geometry::StereoProjection projection;
  projection.fx = camera.fx(), projection.fy = camera.fy(), projection.cx = camera.cx(), projection.cy = camera.cy();
  // sigma from the median residual (robust_scale.h), then a robust refit with it.
  constexpr int kRounds = 3;
  core::SE3 T = T_cw_initial;
  geometry::PoseOptimizerResult result;
  std::vector<double> norms(observations.size());
  for (int round = 0; round < kRounds; ++round) {
    for (std::size_t k = 0; k < observations.size(); ++k) {
      const Eigen::Vector3d p_c = T * observations[k].point_w;
      norms[k] = p_c.z() > 1e-6 ? (observations[k].pixel - camera.project(p_c)).norm()
                                : std::numeric_limits<double>::max();
    }
    refit.sigma_px = pixelNoiseScale(norms);
    for (auto& o : observations) o.inv_sigma2 = 1.0 / (refit.sigma_px * refit.sigma_px);
    result = geometry::optimizePose(observations, T, projection, geometry::PoseOptimizerOptions{});
    T = result.T_cw;
  }
  refit.inliers = result.num_inliers;
  if (refit.inliers >= options.refit_min_points) {
    refit.ok = true;
    refit.T_cw = T;
  }
  return refit;
}

std::vector<ClusterScore> scoreClusters(const std::vector<std::optional<double>>& errors_px,
                                        const std::vector<int>& cluster_of_point, int num_clusters,
                                        const ReprojectionOptions& options) {
  options.check();
  core::require(errors_px.size() == cluster_of_point.size(),
                "scoreClusters: errors and cluster labels differ in number");
  core::require(num_clusters >= 0, "scoreClusters: negative cluster count");
  std::vector<ClusterScore> scores(num_clusters);
  std::vector<double> sum(num_clusters, 0.0);
  for (std::size_t i = 0; i < errors_px.size(); ++i) {
    const int c = cluster_of_point[i];
    if (c < 0 || !errors_px[i]) continue;
    core::require(c < num_clusters, "scoreClusters: cluster label out of range");
    sum[c] += cauchyRho(*errors_px[i] * *errors_px[i], options.cauchy_scale_px);
    ++scores[c].points;
  }
  const double threshold_rho =
      cauchyRho(options.candidate_threshold_px * options.candidate_threshold_px, options.cauchy_scale_px);
  for (int c = 0; c < num_clusters; ++c) {
    ClusterScore& s = scores[c];
    if (s.points < options.min_points_per_cluster) continue;
    s.mean_rho = sum[c] / s.points;
    s.equivalent_px = cauchyEquivalentError(s.mean_rho, options.cauchy_scale_px);
    s.candidate = s.mean_rho > threshold_rho;
  }
  return scores;
}

}  // namespace amos::dynamic
