#pragma once
// Camera pose from 3D world points and their undistorted pixel observations: EPnP inside RANSAC, then a
// Levenberg-Marquardt refinement on the inliers. Deterministic for a given seed.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"

namespace amos::geometry {

struct PnpRansacOptions {
  double reprojection_threshold_px = 2.0;  // inlier if reprojection error below this (undistorted pixels)
  double confidence = 0.99;
  int max_iterations = 300;
  int min_inliers = 15;  // below this the result is a failure
  unsigned seed = 42;
  void check() const;
};

struct PnpResult {
  bool success = false;
  core::SE3 T_cw = core::SE3::Identity();
  std::vector<int> inliers;  // indices into the input arrays
};

PnpResult solvePnpRansac(const std::vector<Eigen::Vector3d>& points_w, const std::vector<Eigen::Vector2d>& pixels,
                         const core::PinholeCamera& camera, const PnpRansacOptions& options);

}  // namespace amos::geometry
