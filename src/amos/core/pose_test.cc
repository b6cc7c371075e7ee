#include "amos/core/pose.h"

#include <gtest/gtest.h>

#include <random>

namespace amos::core {
namespace {

TEST(Pose, ExpLogRoundTrip) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    Vector6d xi;
    for (int k = 0; k < 6; ++k) xi[k] = n(rng);
    xi.tail<3>() *= 0.9;  // keep the angle below pi so the log is unique
    if (xi.tail<3>().norm() > 3.0) continue;
    const Vector6d back = logSE3(expSE3(xi));
    EXPECT_LT((back - xi).norm(), 1e-9) << xi.transpose();
  }
}

// Small rotations are where the closed forms of the Jacobians cancel (a 1e-6 rad rotation used to return its
// translation wrong by 2e-4 of its length).
TEST(Pose, ExpLogRoundTripAtSmallRotations) {
  for (const double angle : {1e-2, 1e-4, 1e-6, 1e-9, 0.0}) {
    Vector6d xi;
    xi << 0.7, -1.1, 0.4, 0.0, 0.0, 0.0;
    xi.tail<3>() = Eigen::Vector3d(0.3, -0.5, 0.8).normalized() * angle;
    EXPECT_LT((logSE3(expSE3(xi)) - xi).norm(), 1e-13) << "angle " << angle;
  }
}

TEST(Pose, ExpOfSmallRotationIsFirstOrder) {
  Eigen::Vector3d phi(1e-14, -2e-14, 0);
  EXPECT_LT((expSO3(phi) - (Eigen::Matrix3d::Identity() + skew(phi))).norm(), 1e-20);
}

TEST(Pose, ConventionMapsWorldIntoCamera) {
  // Camera 1 m along world +x, not rotated: a world point at x=3 lies 2 m along the camera's x axis.
  SE3 T_wc = SE3::Identity();
  T_wc.translation() = Eigen::Vector3d(1, 0, 0);
  const SE3 T_cw = T_wc.inverse();
  EXPECT_NEAR((T_cw * Eigen::Vector3d(3, 0, 0) - Eigen::Vector3d(2, 0, 0)).norm(), 0, 1e-12);
}

TEST(Pose, AdjointMovesATwistBetweenFrames) {
  Vector6d a, xi;
  a << 0.3, -0.2, 0.5, 0.4, -0.7, 0.2;
  xi << -0.1, 0.25, 0.05, 0.3, 0.1, -0.2;
  const SE3 T = expSE3(a);
  const SE3 expected = T * expSE3(xi) * T.inverse();
  EXPECT_LT((expSE3(adjointSE3(T) * xi).matrix() - expected.matrix()).norm(), 1e-12);
}

// Central differences of xi -> logSE3(expSE3(delta) * expSE3(xi)) at delta = 0 against the closed form, at a
// large rotation and at rotations small enough for the series and the closed form's cancellation to meet.
TEST(Pose, LeftJacobianInverseIsTheDerivativeOfTheLog) {
  for (const double angle : {1.9, 0.3, 0.05, 0.0499, 2e-4, 5e-5, 0.0}) {
    Vector6d xi;
    xi << 0.4, -0.3, 0.8, 0.6, -0.2, 0.5;
    xi.tail<3>() = xi.tail<3>().normalized() * angle;
    Matrix6d numeric;
    const double h = 1e-6;
    for (int c = 0; c < 6; ++c) {
      Vector6d d = Vector6d::Zero();
      d[c] = h;
      numeric.col(c) = (logSE3(expSE3(d) * expSE3(xi)) - logSE3(expSE3(-d) * expSE3(xi))) / (2 * h);
    }
    EXPECT_LT((leftJacobianInverseSE3(xi) - numeric).norm(), 1e-7) << "angle " << angle;
  }
}

TEST(Pose, RotationAngle) {
  SE3 T = SE3::Identity();
  T.linear() = expSO3(Eigen::Vector3d(0, 0, 0.3));
  EXPECT_NEAR(rotationAngle(T), 0.3, 1e-12);
}

}  // namespace
}  // namespace amos::core
