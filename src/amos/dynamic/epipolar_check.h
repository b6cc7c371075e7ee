#pragma once
// Stage 2 of the geometric module (paper III-C, Eq. 7-8, after DS-SLAM): a fundamental matrix from the
// last->current correspondences, fitted by RANSAC and refitted without the points far from their epipolar
// lines; a correspondence whose current pixel lies farther than a threshold from its epipolar line moved.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/pose.h"

namespace amos::dynamic {

struct EpipolarOptions {
  // Both thresholds derive from the per-coordinate localisation noise of a tracked corner, sigma ~ 0.5 px
  // (LK converges to ~0.1-0.3 px on corners; the rest covers residual lens distortion and rolling shutter).
  // Dynamic.Epipolar.ransacThreshold: inlier distance for the fit, 2 sigma (~95% of static points, 1 DoF).
  double ransac_threshold_px = 1.0;
  // Dynamic.Epipolar.threshold: a point is dynamic beyond 4 sigma: static noise exceeds it with p ~ 6e-5, and
  // it leaves 1 sigma of margin for the error of the estimated F itself.
  double dynamic_threshold_px = 2.0;
  // Dynamic.Epipolar.confidence / maxIterations: RANSAC stop; with 50% outliers a 7-point sample needs ~590
  // iterations for 99.9%, so 2000 is never the binding limit in practice.
  double confidence = 0.999;
  int max_iterations = 2000;
  // Dynamic.Epipolar.minDynamicPoints: a region is dynamic with at least 2 epipolar violators. One may be an LK
  // mismatch that passed the forward-backward check; two independent ones at p ~ 1e-3 each are ~1e-6.
  int min_dynamic_points = 2;
  // Dynamic.Epipolar.minFitPoints: F is fitted on the tracks outside the potential motion regions when at
  // least this many remain (else on all): 50 keeps the 7-point RANSAC well supported (~7x the sample size).
  int min_fit_points = 50;
  // Dynamic.Epipolar.seed: RANSAC sampling seed (fixed for reproducible runs).
  int seed = 42;
  void check() const;
};

struct FundamentalFit {
  bool ok = false;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();  // maps last-frame pixels to current-frame epipolar lines
  int ransac_inliers = 0;                       // points within ransac_threshold_px of the first (RANSAC) fit
  int refit_points = 0;   // points kept for the second fit (within dynamic_threshold_px of the first)
  int final_inliers = 0;  // points within ransac_threshold_px of the final F
};

// Fits F on undistorted pixel correspondences (at least 15 for the fit to count as ok). Deterministic for a seed.
FundamentalFit fitFundamental(const std::vector<cv::Point2f>& last, const std::vector<cv::Point2f>& current,
                              const EpipolarOptions& options);

// Eq. 7-8: distance [px] of p_current from the epipolar line L = F p_last, |p2^T F p1| / sqrt(A^2 + B^2).
double epipolarDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& p_last, const Eigen::Vector2d& p_current);

// Eq. 7 with the rotation the paper's formula leaves out: F = K^-T [t]x R K^-1 for the motion T_cl (last camera
// -> current camera). Used as a known answer and as a fallback when the correspondences cannot support a fit.
Eigen::Matrix3d fundamentalFromPose(const Eigen::Matrix3d& K, const core::SE3& T_cl);

}  // namespace amos::dynamic
