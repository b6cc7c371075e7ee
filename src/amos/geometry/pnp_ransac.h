#pragma once
// Camera pose from 3D world points and their undistorted pixel observations: minimal-sample hypotheses (AP3P by
// default, EPnP on 5 points as the alternative) inside LO-RANSAC, then a Levenberg-Marquardt refinement on the
// inliers. Deterministic for a given seed.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"

namespace amos::geometry {

// The solver each RANSAC hypothesis comes from.
//  kAp3p: three points, OpenCV's AP3P (Ke & Roumeliotis, CVPR 2017), up to four poses each scored on all
//         correspondences. A three-point sample is all inliers with probability w^3 instead of w^5, so at an
//         inlier ratio w = 0.3 the 99 %-confidence budget is 168 samples instead of 1900 (capped at
//         max_iterations, i.e. a run that may miss the pose), and at w = 0.6 it is 19 instead of 57; each
//         hypothesis is also cheaper than an EPnP (no 12x12 eigen-decomposition). COLMAP's absolute-pose
//         LO-RANSAC uses P3P minimal samples the same way.
//  kEpnp: five points, EPnP (this file's solver before; kept for ablation).
enum class PnpMinimalSolver { kAp3p, kEpnp };

struct PnpRansacOptions {
  double reprojection_threshold_px = 2.0;  // inlier if reprojection error below this (undistorted pixels)
  double confidence = 0.99;
  int max_iterations = 300;
  int min_inliers = 15;  // below this the result is a failure
  unsigned seed = 42;
  PnpMinimalSolver minimal_solver = PnpMinimalSolver::kAp3p;
  // coverage_cols x coverage_rows > 0: of the hypotheses whose support is at least coverage_min_support times the
  // largest support found, the one whose inliers reach the most cells of that grid over the image wins (ties: more
  // inliers); see dynamic::InitialPoseOptions::select_by_coverage. 0 = by number alone (the usual RANSAC).
  int coverage_cols = 0, coverage_rows = 0;
  // Why a floor: a hypothesis that gathers a few chance inliers (within the threshold by luck) scattered over many
  // cells must not beat one that many correspondences support. Within a factor of 2 the numbers say little (a
  // textured person holds twice the corners per pixel of a plain wall), beyond it they do.
  double coverage_min_support = 0.5;
  void check() const;
};

struct PnpResult {
  bool success = false;
  core::SE3 T_cw = core::SE3::Identity();
  std::vector<int> inliers;  // indices into the input arrays
};

// How many cells of a cols x rows grid over a width x height image hold at least one of pixels[indices] (the
// coverage ranking above; also used to compare whole candidate poses).
int countCoveredCells(const std::vector<Eigen::Vector2d>& pixels, const std::vector<int>& indices, double width,
                      double height, int cols, int rows);

PnpResult solvePnpRansac(const std::vector<Eigen::Vector3d>& points_w, const std::vector<Eigen::Vector2d>& pixels,
                         const core::PinholeCamera& camera, const PnpRansacOptions& options);

}  // namespace amos::geometry
