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
// Below this angle the closed forms of the Jacobians' coefficients lose their digits to cancellation (the error of
// (a - sin a) / a^3 grows as 1e-16 / a^2, that of (a^2 + 2 cos a - 2) / a^4 as 1e-16 / a^4); their Taylor series to
// the a^4 term are then exact to 1e-13 (the first term left out is below a^6 / 5000).
constexpr double kSeriesAngle = 0.05;

// Left Jacobian of SO(3) and its inverse (Barfoot, "State Estimation for Robotics", eq. 7.77 / 7.79).
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& phi) {
  const double a = phi.norm(), a2 = a * a;
  const Eigen::Matrix3d W = skew(phi);
  const double c1 = a < kSeriesAngle ? 0.5 - a2 / 24 + a2 * a2 / 720 : (1 - std::cos(a)) / a2;
  const double c2 = a < kSeriesAngle ? 1.0 / 6 - a2 / 120 + a2 * a2 / 5040 : (a - std::sin(a)) / (a2 * a);
  return Eigen::Matrix3d::Identity() + c1 * W + c2 * W * W;
}

Eigen::Matrix3d leftJacobianInverse(const Eigen::Vector3d& phi) {
  const double a = phi.norm(), a2 = a * a;
  const Eigen::Matrix3d W = skew(phi);
  // (1 - (a / 2) cot(a / 2)) / a^2
  const double c = a < kSeriesAngle ? 1.0 / 12 + a2 / 720 + a2 * a2 / 30240
                                    : (1.0 / a2) * (1 - (a * std::sin(a)) / (2 * (1 - std::cos(a))));
  return Eigen::Matrix3d::Identity() - 0.5 * W + c * W * W;
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

Matrix6d adjointSE3(const SE3& T) {
  Matrix6d ad = Matrix6d::Zero();
  ad.topLeftCorner<3, 3>() = T.linear();
  ad.topRightCorner<3, 3>() = skew(T.translation()) * T.linear();
  ad.bottomRightCorner<3, 3>() = T.linear();
  return ad;
}

namespace {
// The coupling block Q(rho, phi) of SE(3)'s left Jacobian (Barfoot eq. 7.86), its coefficients by their series
// at small angles (kSeriesAngle).
Eigen::Matrix3d leftJacobianCoupling(const Eigen::Vector3d& rho, const Eigen::Vector3d& phi) {
  const double a = phi.norm(), a2 = a * a;
  double c1 = 1.0 / 6 - a2 / 120 + a2 * a2 / 5040;
  double c2 = 1.0 / 24 - a2 / 720 + a2 * a2 / 40320;
  double c3 = 1.0 / 120 - a2 / 2520 + a2 * a2 / 120960;
  if (a >= kSeriesAngle) {
    const double s = std::sin(a), c = std::cos(a);
    c1 = (a - s) / (a2 * a);
    c2 = (a2 + 2 * c - 2) / (2 * a2 * a2);
    c3 = (2 * a - 3 * s + a * c) / (2 * a2 * a2 * a);
  }
  const Eigen::Matrix3d P = skew(phi), R = skew(rho);
  const Eigen::Matrix3d PR = P * R, RP = R * P, PRP = PR * P;
  return 0.5 * R + c1 * (PR + RP + PRP) + c2 * (P * PR + RP * P - 3 * PRP) + c3 * (PRP * P + P * PRP);
}
}  // namespace

Matrix6d leftJacobianInverseSE3(const Vector6d& xi) {
  const Eigen::Matrix3d Jinv = leftJacobianInverse(xi.tail<3>());
  Matrix6d out = Matrix6d::Zero();
  out.topLeftCorner<3, 3>() = Jinv;
  out.topRightCorner<3, 3>() = -Jinv * leftJacobianCoupling(xi.head<3>(), xi.tail<3>()) * Jinv;
  out.bottomRightCorner<3, 3>() = Jinv;
  return out;
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
