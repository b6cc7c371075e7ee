#include "amos/geometry/triangulation.h"

#include <Eigen/SVD>
#include <cmath>

namespace amos::geometry {

std::optional<Eigen::Vector3d> triangulateDlt(const Eigen::Vector2d& x1, const core::SE3& T_c1w,
                                              const Eigen::Vector2d& x2, const core::SE3& T_c2w) {
  const Eigen::Matrix<double, 3, 4> P1 = T_c1w.matrix().topRows<3>();
  const Eigen::Matrix<double, 3, 4> P2 = T_c2w.matrix().topRows<3>();
  // Each view gives two rows of A X = 0: x * P.row(2) - P.row(0) and y * P.row(2) - P.row(1).
  Eigen::Matrix4d A;
  A.row(0) = x1.x() * P1.row(2) - P1.row(0);
  A.row(1) = x1.y() * P1.row(2) - P1.row(1);
  A.row(2) = x2.x() * P2.row(2) - P2.row(0);
  A.row(3) = x2.y() * P2.row(2) - P2.row(1);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X(3)) < 1e-12) return std::nullopt;
  const Eigen::Vector3d p = X.head<3>() / X(3);
  if (!p.allFinite()) return std::nullopt;
  return p;
}

}  // namespace amos::geometry
