#pragma once
// Stage 1 of the geometric module (paper III-C, Eq. 5-6): every tracked corner with a valid depth in the last
// frame becomes a temporary map point P = T_wl * backproject(u_last, Z) (Eq. 6); it is reprojected into the
// current frame with the current frame's initial pose; each geometric cluster scores the Cauchy-robust mean
// of its points' squared reprojection errors (Eq. 5). Clusters scoring above a threshold are candidates.
// The pose refit below re-estimates the current pose on the tracks outside the candidates, as the paper refits F
// without its violators (III-C), so that the errors can be judged under a pose that the movers did not bias.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/geometry/pose_optimizer.h"

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
  // Dynamic.Reprojection.refitPose: re-estimate the current pose (motion-only, robust) on the tracks with depth
  // outside the candidate and prior regions, and judge every cluster again under it (see confirmThreshold).
  // The epipolar test cannot see motion along the epipolar lines (an object moving parallel to the camera's
  // translation, e.g. pushed sideways while the camera slides sideways); the depth-based error can, once the
  // pose error it was guarding against is removed.
  bool refit_pose = true;
  // Dynamic.Reprojection.refitMinPoints: the refit counts only with at least this many inliers; 30 constrain
  // 6 pose parameters ~5x over, with a pose error well under the 0.3 px noise per point.
  int refit_min_points = 30;
  // Dynamic.Reprojection.confirmSigmas / confirmThreshold: a cluster is dynamic when its equivalent error under
  // the refitted pose exceeds max(confirmThreshold, confirmSigmas * sigma), sigma being the static tracks' noise
  // scale that the refit measured (PoseRefit::sigma_px). Under the refit only the tracks' own noise remains, so
  // the bar follows it: for Gaussian noise the RMS of 3 errors exceeds 2.7 sigma with p = 0.001, and 5 sigma
  // leaves room for heavier tails (LK slips) and spatially correlated errors. The floor, 1 px, covers what a
  // median-based sigma does not see on a real sensor (residual distortion, depth-to-colour registration, rolling
  // shutter: a few tenths of a pixel each). On clean images (sigma ~ 0.1-0.2 px) a mover is found from ~1 px
  // of motion per frame, on noisy ones (sigma ~ 0.5 px) from 2.5 px; the candidate threshold above, which must
  // also absorb the initial pose's bias, stays at 3 px.
  double confirm_sigmas = 5.0;
  double confirm_threshold_px = 1.0;
  // Dynamic.Reprojection.intervalErrors: tracks without a trusted depth (depth edge, holes) enter Eq. 5 with the
  // smallest error any depth of their LK window allows (intervalResiduals); false = they are left out (paper).
  bool interval_errors = true;
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

// Lengths of residual vectors [px] (empty stays empty).
std::vector<std::optional<double>> residualNorms(const std::vector<std::optional<Eigen::Vector2d>>& residuals);

// Reprojection error [px] of each world point against the track's current pixel under T_cw_current; empty when
// the point has none or lies behind the camera.
std::vector<std::optional<double>> reprojectionErrors(const std::vector<PointTrack>& tracks,
                                                      const std::vector<std::optional<Eigen::Vector3d>>& points_w,
                                                      const core::SE3& T_cw_current, const core::PinholeCamera& camera);

// The residual vectors behind reprojectionErrors: current undistorted pixel minus the projection [px].
std::vector<std::optional<Eigen::Vector2d>> reprojectionResiduals(
    const std::vector<PointTrack>& tracks, const std::vector<std::optional<Eigen::Vector3d>>& points_w,
    const core::SE3& T_cw_current, const core::PinholeCamera& camera);

// The depths a track's last pixel may have had when no single depth can be trusted (it sits on a depth edge or
// among holes, so backProjectTracks gave it no point): the range of the valid depths within radius_px of it, open
// to infinity when that window holds holes (a hole may be a surface beyond the sensor's range or the far side of an
// occlusion band). Empty when the window holds no valid depth within max_depth_m.
struct DepthInterval {
  double near_m = 0;
  double far_m = 0;  // infinity when open
};
std::vector<std::optional<DepthInterval>> trackDepthIntervals(const std::vector<PointTrack>& tracks,
                                                              const cv::Mat& last_depth, int radius_px,
                                                              const ReprojectionOptions& options);

// The smallest residual a static point could have: wherever on its last pixel's ray within the depth interval the
// point was, a static point projects under T_cw_current onto the segment that this part of the ray projects to.
// Returns the current undistorted pixel minus the nearest point of that segment [px] (a lower bound of the
// reprojection error of every depth in the interval; zero when the pixel lies on the segment). Empty without an
// interval or when the near end lies behind the camera.
std::vector<std::optional<Eigen::Vector2d>> intervalResiduals(const std::vector<PointTrack>& tracks,
                                                              const std::vector<std::optional<DepthInterval>>& intervals,
                                                              const core::SE3& T_cw_last, const core::SE3& T_cw_current,
                                                              const core::PinholeCamera& camera);

struct PoseRefit {
  bool ok = false;                            // enough inliers (refit_min_points)
  core::SE3 T_cw = core::SE3::Identity();     // the refitted pose (the initial one when !ok)
  int points = 0;                             // tracks offered to the refit
  int inliers = 0;                            // of which inliers of the final pose
  double sigma_px = 0;                        // the noise scale of the last round
};

// The confirmation threshold for a refit (see confirm_sigmas).
double confirmThreshold(const PoseRefit& refit, const ReprojectionOptions& options);

// Motion-only refinement of T_cw_initial on the tracks with use[i] and a world point: Gauss-Newton with a Huber
// kernel and chi-square outlier rounds (geometry::optimizePose), in a few rounds that each re-estimate the noise
// scale sigma from the median residual of the current pose (median |r| = 1.18 sigma for 2D Gaussian noise;
// at least 0.1 px, LK's floor on clean images). A fixed, generous sigma would let a mover that slipped into the
// set stay an inlier: sliding the pose along the translation/rotation ambiguity of a shallow scene (x against
// yaw) costs the static points a fraction of a pixel and halves a slow mover's error. With sigma matched to the
// static points the mover falls outside 2.45 sigma and the pose returns to the static optimum.
PoseRefit refitPose(const std::vector<PointTrack>& tracks, const std::vector<std::optional<Eigen::Vector3d>>& points_w,
                    const std::vector<bool>& use, const core::SE3& T_cw_initial, const core::PinholeCamera& camera,
                    const ReprojectionOptions& options);

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
