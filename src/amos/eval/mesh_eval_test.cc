#include "amos/eval/mesh_eval.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"

namespace amos::eval {
namespace {

std::vector<Eigen::Vector3d> plane(double z, double step) {
  std::vector<Eigen::Vector3d> p;
  for (double x = 0; x <= 1; x += step)
    for (double y = 0; y <= 1; y += step) p.emplace_back(x, y, z);
  return p;
}

// Where a person stood on the plane: a column 0.4 x 0.4 x 2 m above (0.3, 0.3).
synth::SweptVolume personColumn() {
  synth::SweptVolume swept(0.02);
  for (double x = 0.11; x < 0.5; x += 0.02)
    for (double y = 0.11; y < 0.5; y += 0.02)
      for (double z = 0.01; z < 2.0; z += 0.02) swept.markPoint({x, y, z});
  return swept;
}

TEST(MeshEval, ScoresAccuracyCompletenessAndGhosts) {
  const auto truth = plane(0, 0.01);
  std::vector<Eigen::Vector3d> mesh;
  for (const auto& p : plane(0.005, 0.02)) {
    if (p.x() < 0.5) mesh.push_back(p);  // half the surface, 5 mm off
  }
  const std::size_t surface = mesh.size();
  for (int i = 0; i < 10; ++i) mesh.emplace_back(0.3, 0.3, 1.0 + 0.1 * i);  // a person standing on it
  const MeshScore s = scoreMesh(mesh, truth, personColumn(), 0.04, 0.04);
  EXPECT_EQ(s.vertices, surface + 10);
  EXPECT_EQ(s.ghosts, 10u);
  EXPECT_EQ(s.off_surface, 10u);
  EXPECT_NEAR(s.ghost_share, 10.0 / (surface + 10), 1e-12);
  EXPECT_NEAR(s.accuracy_median_m, 0.005, 1e-9);
  EXPECT_NEAR(s.completeness, 0.54, 0.03);  // half the plane and the 4 cm beyond its edge
  EXPECT_EQ(s.swept_cells, 20u * 20u * 100u);
}

TEST(MeshEval, AGhostIsInTheSweepAndOffTheStaticSurface) {
  const auto truth = plane(0, 0.01);
  const synth::SweptVolume swept = personColumn();
  const std::vector<Eigen::Vector3d> mesh = {
      {0.3, 0.3, 1.2},    // inside the sweep, off the surface: a ghost
      {0.3, 0.3, 0.005},  // inside the sweep (the floor under the person's feet), on the surface: not a ghost
      {0.8, 0.8, 0.5},    // off the surface, far from the sweep: not a ghost, off the surface
      {0.52, 0.3, 0.9},   // 2 cm beside the sweep, off the surface: a ghost by the sweep's margin
      {0.56, 0.3, 0.9},   // 6 cm beside it: off the surface only
  };
  const MeshScore s = scoreMesh(mesh, truth, swept, 0.02, 0.03);
  EXPECT_EQ(s.ghosts, 2u);
  EXPECT_EQ(s.off_surface, 4u);
  EXPECT_EQ(s.in_sweep, 3u);
  ASSERT_EQ(s.ghost_points.size(), 2u);
  EXPECT_EQ(s.ghost_points[0], mesh[0]);
  EXPECT_NEAR(s.ghost_share, 2.0 / 5, 1e-12);
  EXPECT_NEAR(s.off_surface_share, 4.0 / 5, 1e-12);
  // Without movers (an empty sweep) nothing is a ghost, whatever is off the surface.
  const MeshScore none = scoreMesh(mesh, truth, synth::SweptVolume(0.02), 0.02, 0.03);
  EXPECT_EQ(none.ghosts, 0u);
  EXPECT_EQ(none.off_surface, 4u);
}

TEST(MeshEval, AnEmptyMeshCoversNothing) {
  const MeshScore s = scoreMesh({}, plane(0, 0.05), personColumn(), 0.04, 0.04);
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

TEST(MeshEval, AMeshWithAVertexThatIsNotFiniteIsAnErrorNamingTheFile) {
  const std::filesystem::path file = testing::scratchDirForThisTest("amos_nan_mesh_") / "mesh.ply";
  std::ofstream(file) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                         "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n";
  try {
    readMeshVertices(file.string());
    ADD_FAILURE() << "read a mesh with a NaN vertex";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ": vertex 1 of 3 is not finite"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace amos::eval
