#include "amos/core/distortion.h"

#include <Eigen/LU>

namespace amos::core {

Eigen::Vector2d RadialTangential::distort(const Eigen::Vector2d& xn, Eigen::Matrix2d* J) const {
  const double x = xn.x(), y = xn.y();
  const double x2 = x * x, y2 = y * y, xy = x * y, r2 = x2 + y2;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const Eigen::Vector2d out(x * radial + 2 * p1 * xy + p2 * (r2 + 2 * x2),
                            y * radial + p1 * (r2 + 2 * y2) + 2 * p2 * xy);
  if (J) {
    const double d_radial_d_r2 = k1 + r2 * (2 * k2 + 3 * k3 * r2);
    (*J)(0, 0) = radial + 2 * x2 * d_radial_d_r2 + 2 * p1 * y + 6 * p2 * x;
    (*J)(0, 1) = 2 * xy * d_radial_d_r2 + 2 * p1 * x + 2 * p2 * y;
    (*J)(1, 0) = (*J)(0, 1);
    (*J)(1, 1) = radial + 2 * y2 * d_radial_d_r2 + 6 * p1 * y + 2 * p2 * x;
  }
  return out;
}

Eigen::Vector2d RadialTangential::undistort(const Eigen::Vector2d& xd) const {
  if (none()) return xd;
  Eigen::Vector2d xn = xd;
  Eigen::Matrix2d J;
  for (int it = 0; it < 20; ++it) {
    const Eigen::Vector2d r = distort(xn, &J) - xd;
    if (r.squaredNorm() < 1e-28) break;
    xn -= J.inverse() * r;
  }
  return xn;
}

}  // namespace amos::core
