#pragma once
// Stage 1 of the geometric module (paper III-C, Eq. 5-6): every tracked corner with a valid depth in the last
// frame becomes a temporary map point P = T_wl * backproject(u_last, Z) (Eq. 6); it is reprojected into the
// current frame with the current frame's initial pose; each geometric cluster scores the Cauchy-robust mean
// of its points' squared reprojection errors (Eq. 5). Clusters scoring above a threshold are candidates.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/corner_tracking.h"

namespace amos::dynamic {

struct ReprojectionOptions {
  // Dynamic.Reprojection.cauchyScale: c [px] in rho(s) = c^2 log(1 + s / c^2). rho must not suppress the signal
  // (object motion of a few px per frame) but only gross errors (LK mismatches, depths read across an edge:
  // tens of px). Static errors (LK ~0.3 px + initial pose error ~1 px) stay in rho's quadratic range below c;
  // a 6 px motion still weighs 2.3 c^2 against 0.2 c^2 for a 1 px static error, while a 100 px mismatch weighs
  // 7.8 c^2 instead of 2500 c^2, so one mismatch among ~10 static points cannot lift their mean above the
  // threshold. c = 2 px sits between the two.
  double cauchy_scale_px = 2.0;
  // Dynamic.Reprojection.threshold: a cluster is a candidate when its mean rho exceeds rho(t^2), i.e. its
  // "equivalent" error exceeds t = 3 px: above what static noise plus a ~1 px initial-pose bias reaches
  // (equivalent ~1.5 px), below the ~6 px a walking person (1 m/s at 3 m, 30 Hz, f ~ 540 px) moves per frame.
  // The candidate stage only nominates; the epipolar stage decides, so it leans towards recall.
  double candidate_threshold_px = 3.0;
  // Dynamic.Reprojection.minPoints: a mean over fewer than 3 errors is too easily one bad track.
  int min_points_per_cluster = 3;
  // Dynamic.Reprojection.maxDepth: RGB-D depth beyond 6 m has sigma(z) > 6 cm and is often spurious.
  double max_depth_m = 6.0;
  // Dynamic.Reprojection.depthEdgeRatio: a point whose 5x5 depth neighbourhood (the pixels that shape a
  // Shi-Tomasi corner) spans more than this fraction of its depth, or holds an invalid depth, sits on a depth
  // edge, where the corner may move with the other side. 5%: indoor object borders are >= 0.3 m deep (10% at
  // 3 m); noise (6 sigma(z)) stays below 5% of z up to 4.5 m; a plane seen 70 deg off its normal changes depth
  // by ~2% of z over +-2 px.
  double depth_edge_ratio = 0.05;
  void check() const;
};

// rho of Eq. 5, the Cauchy loss of a squared error: c^2 log(1 + s / c^2).
double cauchyRho(double squared_error, double scale);
// The error magnitude whose rho equals a given mean rho (inverse of cauchyRho, then sqrt): turns a cluster score
// into pixels.
double cauchyEquivalentError(double mean_rho, double scale);

// Eq. 6: world points of the tracks' last-frame pixels, from the last depth image (CV_32F metres) and the last
// frame's pose. Empty optional when the depth is invalid, too far, within 2 px of the image edge or on a depth
// edge (see ReprojectionOptions).
// Pixels are raw (distorted) image coordinates, undistorted with the camera before back-projection.
std::vector<std::optional<Eigen::Vector3d>> backProjectTracks(const std::vector<PointTrack>& tracks,
                                                              const cv::Mat& last_depth, const core::SE3& T_cw_last,
                                                              const core::PinholeCamera& camera,
                                                              const ReprojectionOptions& options);

// Reprojection error [px] of each world point against the track's current pixel under T_cw_current; empty when
// the point has none or lies behind the camera.
std::vector<std::optional<double>> reprojectionErrors(const std::vector<PointTrack>& tracks,
                                                      const std::vector<std::optional<Eigen::Vector3d>>& points_w,
                                                      const core::SE3& T_cw_current, const core::PinholeCamera& camera);

struct ClusterScore {
  int points = 0;            // errors that entered the mean
  double mean_rho = 0;       // Eq. 5 (0 when points < min_points_per_cluster)
  double equivalent_px = 0;  // cauchyEquivalentError(mean_rho)
  bool candidate = false;    // potential motion region
};

// Eq. 5 per cluster. cluster_of_point[i] in [0, num_clusters) or -1 (point left out, e.g. in a border block).
std::vector<ClusterScore> scoreClusters(const std::vector<std::optional<double>>& errors_px,
                                        const std::vector<int>& cluster_of_point, int num_clusters,
                                        const ReprojectionOptions& options);

}  // namespace amos::dynamic
