#pragma once
// Pose-only optimisation of one RGB-D frame against known 3D points (ORB-SLAM2's "motion-only BA"):
// Gauss-Newton with Levenberg-Marquardt damping on SE(3) (left perturbation, see core/pose.h), Huber kernel, and
// several rounds of outlier classification by a chi-square test, so that an outlier can come back once the pose
// has moved. An observation with a virtual right coordinate u_r (RGB-D: u_r = u - bf / z) has a 3-vector residual
// (u, v, u_r) and the 3-dof chi-square threshold; one without has (u, v) and the 2-dof threshold.
#include <Eigen/Core>
#include <vector>

#include "amos/core/pose.h"

namespace amos::geometry {

// Pinhole projection and stereo baseline used by the optimisers (undistorted pixels).
struct StereoProjection {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  double bf = 0;  // baseline times fx (Camera.bf); u_r = u - bf / z
};

struct PoseObservation {
  Eigen::Vector3d point_w = Eigen::Vector3d::Zero();
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // undistorted
  double u_right = -1;   // < 0: no right coordinate (monocular residual)
  double inv_sigma2 = 1; // 1 / sigma^2 of the keypoint's pyramid level
  bool outlier = false;  // initial classification (outliers start excluded)
};

struct PoseOptimizerOptions {
  double chi2_mono = 5.991;    // 95% chi-square, 2 dof
  double chi2_stereo = 7.815;  // 95% chi-square, 3 dof
  int rounds = 4;              // outlier classification rounds
  int iterations_per_round = 10;
  int robust_rounds = 2;       // the Huber kernel is used in the first rounds only (as ORB-SLAM2 does)
  void check() const;
};

struct PoseOptimizerResult {
  core::SE3 T_cw = core::SE3::Identity();
  std::vector<bool> outlier;  // per observation, after the last round
  int num_inliers = 0;
  double final_chi2 = 0;      // sum over inliers
};

// Refines T_cw from `initial_T_cw`. Observations behind the camera count as outliers.
PoseOptimizerResult optimizePose(const std::vector<PoseObservation>& observations, const core::SE3& initial_T_cw,
                                 const StereoProjection& projection, const PoseOptimizerOptions& options);

// Residual (observed - predicted) of one observation for a pose; returns false when the point is behind the
// camera. residual has 2 or 3 entries (3 when u_right >= 0).
bool poseObservationResidual(const PoseObservation& obs, const core::SE3& T_cw, const StereoProjection& projection,
                             Eigen::Vector3d& residual, Eigen::Vector3d& point_c);

// The same residual and its Jacobian for the left perturbation T <- exp(delta) T (rows 0-1, or 0-2 with u_right);
// false when the point is behind the camera.
bool poseObservationJacobian(const PoseObservation& obs, const core::SE3& T_cw, const StereoProjection& projection,
                             Eigen::Vector3d& residual, Eigen::Matrix<double, 3, 6>& J);

}  // namespace amos::geometry
