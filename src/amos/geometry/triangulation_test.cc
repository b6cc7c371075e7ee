#include "amos/geometry/triangulation.h"

#include <gtest/gtest.h>

namespace amos::geometry {
namespace {

TEST(Triangulation, RecoversPointFromTwoViews) {
  core::Vector6d xi1, xi2;
  xi1 << 0.1, 0.0, -0.2, 0.02, 0.1, 0.0;
  xi2 << -0.2, 0.05, 0.1, -0.05, 0.0, 0.1;
  const core::SE3 T1 = core::expSE3(xi1), T2 = core::expSE3(xi2);
  const Eigen::Vector3d p(0.3, -0.2, 2.5);
  const Eigen::Vector3d c1 = T1 * p, c2 = T2 * p;
  const auto X = triangulateDlt(c1.head<2>() / c1.z(), T1, c2.head<2>() / c2.z(), T2);
  ASSERT_TRUE(X.has_value());
  EXPECT_LT((*X - p).norm(), 1e-9);
}

TEST(Triangulation, ParallelRaysGiveNoPoint) {
  // Two cameras side by side looking along the same ray direction: the rays meet at infinity.
  const core::SE3 T1 = core::SE3::Identity();
  core::SE3 T2 = core::SE3::Identity();
  T2.translation() = Eigen::Vector3d(-0.5, 0, 0);
  EXPECT_FALSE(triangulateDlt({0.1, 0.1}, T1, {0.1, 0.1}, T2).has_value());
}

}  // namespace
}  // namespace amos::geometry
