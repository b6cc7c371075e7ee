#pragma once
// OpenCV's radial-tangential lens model (k1 k2 p1 p2 k3) on normalised image coordinates (x/z, y/z), with its 2x2
// Jacobian, for code that projects many points into raw (distorted) images and needs derivatives: the photometric
// refinement samples the camera's own pixel grid instead of undistorting whole images (issue 42).
#include <Eigen/Core>

namespace amos::core {

struct RadialTangential {
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;

  bool none() const { return k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && k3 == 0; }
  // Distorted normalised coordinates of undistorted ones; J (optional) receives d(distorted)/d(undistorted).
  Eigen::Vector2d distort(const Eigen::Vector2d& xn, Eigen::Matrix2d* J = nullptr) const;
  // The inverse, by Newton's method on distort() (converges to round-off where the model is invertible, i.e.
  // inside the image of a real lens). Unchanged input when there is no distortion.
  Eigen::Vector2d undistort(const Eigen::Vector2d& xd) const;
};

}  // namespace amos::core
