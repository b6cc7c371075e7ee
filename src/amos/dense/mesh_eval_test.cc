#include "amos/dense/mesh_eval.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace amos::dense {
namespace {

std::vector<Eigen::Vector3d> plane(double z, double step) {
  std::vector<Eigen::Vector3d> p;
  for (double x = 0; x <= 1; x += step)
    for (double y = 0; y <= 1; y += step) p.emplace_back(x, y, z);
  return p;
}

TEST(MeshEval, ScoresAccuracyCompletenessAndGhosts) {
  const auto truth = plane(0, 0.01);
  std::vector<Eigen::Vector3d> mesh;
  for (const auto& p : plane(0.005, 0.02)) {
    if (p.x() < 0.5) mesh.push_back(p);  // half the surface, 5 mm off
  }
  const std::size_t surface = mesh.size();
  for (int i = 0; i < 10; ++i) mesh.emplace_back(0.3, 0.3, 1.0 + 0.1 * i);  // a person standing on it
  const MeshScore s = scoreMesh(mesh, truth, 0.04);
  EXPECT_EQ(s.vertices, surface + 10);
  EXPECT_EQ(s.ghosts, 10u);
  EXPECT_NEAR(s.ghost_share, 10.0 / (surface + 10), 1e-12);
  EXPECT_NEAR(s.accuracy_median_m, 0.005, 1e-9);
  EXPECT_NEAR(s.completeness, 0.54, 0.03);  // half the plane and the 4 cm beyond its edge
}

TEST(MeshEval, AnEmptyMeshCoversNothing) {
  const MeshScore s = scoreMesh({}, plane(0, 0.05), 0.04);
  EXPECT_EQ(s.completeness, 0.0);
  EXPECT_EQ(s.ghosts, 0u);
}

TEST(MeshEval, AlignsAStillCameraByItsPoses) {
  // A camera that does not move: positions alone cannot give the rotation, poses can.
  core::SE3 T_gt_est = core::SE3::Identity();
  T_gt_est.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  T_gt_est.translation() = Eigen::Vector3d(1, -2, 0.5);
  std::vector<io::StampedPose> gt, est;
  for (int i = 0; i < 10; ++i) {
    core::SE3 T_wc = core::SE3::Identity();
    T_wc.linear() = Eigen::AngleAxisd(0.001 * i, Eigen::Vector3d::UnitY()).toRotationMatrix();
    est.push_back({double(i), T_wc});
    gt.push_back({double(i), T_gt_est * T_wc});
  }
  EXPECT_TRUE(alignByPoses(gt, est).isApprox(T_gt_est, 1e-9));
}

}  // namespace
}  // namespace amos::dense
