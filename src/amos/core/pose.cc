#include "amos/core/pose.h"

#include <cmath>

namespace amos::core {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d expSO3(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity() + skew(phi);
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

Eigen::Vector3d logSO3(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

namespace {
// Left Jacobian of SO(3) and its inverse (Barfoot, "State Estimation for Robotics", eq. 7.77 / 7.79).
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  const Eigen::Matrix3d W = skew(phi);
  if (a < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * W;
  return Eigen::Matrix3d::Identity() + (1 - std::cos(a)) / (a * a) * W + (a - std::sin(a)) / (a * a * a) * W * W;
}

Eigen::Matrix3d leftJacobianInverse(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  const Eigen::Matrix3d W = skew(phi);
  if (a < 1e-8) return Eigen::Matrix3d::Identity() - 0.5 * W;
  const double coeff = (1.0 / (a * a)) * (1 - (a * std::sin(a)) / (2 * (1 - std::cos(a))));
  return Eigen::Matrix3d::Identity() - 0.5 * W + coeff * W * W;
}
}  // namespace

SE3 expSE3(const Vector6d& xi) {
  const Eigen::Vector3d rho = xi.head<3>();
  const Eigen::Vector3d phi = xi.tail<3>();
  SE3 T = SE3::Identity();
  T.linear() = expSO3(phi);
  T.translation() = leftJacobian(phi) * rho;
  return T;
}

Vector6d logSE3(const SE3& T) {
  Vector6d xi;
  const Eigen::Vector3d phi = logSO3(T.linear());
  xi.head<3>() = leftJacobianInverse(phi) * T.translation();
  xi.tail<3>() = phi;
  return xi;
}

SE3 makeSE3(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  SE3 T = SE3::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

double rotationAngle(const SE3& T) {
  // Clamp protects acos against round-off just outside [-1, 1].
  const double c = std::clamp((T.linear().trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c);
}

double translationNorm(const SE3& T) { return T.translation().norm(); }

}  // namespace amos::core
