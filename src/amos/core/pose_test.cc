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

TEST(Pose, RotationAngle) {
  SE3 T = SE3::Identity();
  T.linear() = expSO3(Eigen::Vector3d(0, 0, 0.3));
  EXPECT_NEAR(rotationAngle(T), 0.3, 1e-12);
}

}  // namespace
}  // namespace amos::core
