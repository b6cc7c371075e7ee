#pragma once
// Pose convention, written down once for the whole project:
//   T_ab is the rigid transform that maps points expressed in frame b into frame a: p_a = T_ab * p_b.
//   T_cw maps world points into the camera; T_wc = T_cw.inverse() is the camera pose in the world (what the TUM
//   trajectory format stores). Camera frame: x right, y down, z forward (optical axis).
// Tangent vectors are ordered [rho (translation), phi (rotation)] and perturbations are applied on the left:
//   T_new = expSE3(delta) * T.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace amos::core {

using SE3 = Eigen::Isometry3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Skew-symmetric matrix [v]x such that [v]x * w = v.cross(w).
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

// Rodrigues: rotation matrix of the rotation vector phi (axis * angle).
Eigen::Matrix3d expSO3(const Eigen::Vector3d& phi);
// Inverse of expSO3 for angles in [0, pi].
Eigen::Vector3d logSO3(const Eigen::Matrix3d& R);

// SE(3) exponential of [rho, phi] using the left Jacobian, so that expSE3 and logSE3 are exact inverses.
SE3 expSE3(const Vector6d& xi);
Vector6d logSE3(const SE3& T);

// Adjoint of T on tangent vectors: expSE3(adjointSE3(T) * xi) = T * expSE3(xi) * T^-1.
Matrix6d adjointSE3(const SE3& T);
// Inverse of SE(3)'s left Jacobian at xi (Barfoot, "State Estimation for Robotics", eq. 7.85-7.86): to first order
// in delta, logSE3(expSE3(delta) * expSE3(xi)) = xi + leftJacobianInverseSE3(xi) * delta.
Matrix6d leftJacobianInverseSE3(const Vector6d& xi);

// Builds a pose from a translation and a (not necessarily normalised) quaternion.
SE3 makeSE3(const Eigen::Quaterniond& q, const Eigen::Vector3d& t);

// Rotation angle of T in radians, translation norm in metres.
double rotationAngle(const SE3& T);
double translationNorm(const SE3& T);

}  // namespace amos::core
