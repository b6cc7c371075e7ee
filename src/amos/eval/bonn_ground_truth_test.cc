#include "amos/eval/bonn_ground_truth.h"

#include <gtest/gtest.h>

#include <string>

#include "amos/eval/evaluate.h"
#include "amos/testing/shared_data.h"

namespace amos::eval {
namespace {

bool isRotation(const Eigen::Matrix3d& R, double tolerance) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < tolerance &&
         std::abs(R.determinant() - 1.0) < tolerance;
}

TEST(BonnGroundTruth, CalibrationIsTheClosestRotationToTheScaledBlock) {
  const core::SE3 T_m = bonnMarkerToCameraCalibration();
  EXPECT_TRUE(isRotation(T_m.linear(), 1e-12));
  Eigen::Matrix3d raw;
  raw << 1.0157, 0.1828, -0.2389, 0.0009, -0.8431, -0.6413, -0.3009, 0.6147, -0.8085;
  // The readme's block is about 1.059 x a rotation: dividing by its scale must land close to ours.
  const double scale = std::cbrt(raw.determinant());
  EXPECT_NEAR(scale, 1.059, 0.005);
  EXPECT_LT((raw / scale - T_m.linear()).norm(), 0.05);
  EXPECT_EQ(T_m.translation(), Eigen::Vector3d(0.0113, -0.0098, 0.0111));
}

TEST(BonnGroundTruth, FormulaOnOnePose) {
  const core::SE3 T_marker = core::expSE3((core::Vector6d() << 0.5, -1.7, 1.5, 0.3, 0.2, -2.9).finished());
  Eigen::Matrix4d T_ros;
  T_ros << -1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1;
  const Eigen::Matrix4d expected =
      T_ros.transpose() * T_marker.matrix() * T_ros * bonnMarkerToCameraCalibration().matrix();
  const core::SE3 camera = bonnMarkerToCamera(T_marker);
  EXPECT_LT((camera.matrix() - expected).norm(), 1e-12);
  EXPECT_TRUE(isRotation(camera.linear(), 1e-12));
}

// The real Bonn ground truth: converted poses are rigid; a perfect camera trajectory has ~zero RPE against the
// converted ground truth but large RPE against the raw marker file, while ATE hardly changes (data README).
TEST(BonnGroundTruth, RpeNeedsTheConvertedGroundTruthAteDoesNot) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev/groundtruth.txt");
  const auto marker = io::readTumTrajectory(testing::dataPath("bonn_crowd_dev/groundtruth.txt"));
  ASSERT_GT(marker.size(), 300u);
  const auto camera = bonnMarkerToCamera(marker);
  ASSERT_EQ(camera.size(), marker.size());
  for (const auto& p : camera) ASSERT_TRUE(isRotation(p.T_wc.linear(), 1e-9));

  // A perfect estimate of the camera, in its own world frame (first pose at the origin), as SLAM would give it.
  std::vector<io::StampedPose> estimate;
  const core::SE3 to_first = camera.front().T_wc.inverse();
  for (const auto& p : camera) estimate.push_back({p.timestamp, to_first * p.T_wc});

  const EvaluationResult vs_camera = evaluate(camera, estimate);
  const EvaluationResult vs_marker = evaluate(marker, estimate);
  std::printf("perfect camera estimate: vs converted GT ATE %.4f m RPE %.4f m %.3f deg; vs raw marker GT ATE %.4f m "
              "RPE %.4f m %.3f deg (%zu pairs)\n",
              vs_camera.ate_rmse_m, vs_camera.rpe_trans_rmse_m, vs_camera.rpe_rot_rmse_deg, vs_marker.ate_rmse_m,
              vs_marker.rpe_trans_rmse_m, vs_marker.rpe_rot_rmse_deg, vs_marker.rpe_pairs);
  EXPECT_GT(vs_camera.rpe_pairs, 250u);
  EXPECT_LT(vs_camera.ate_rmse_m, 1e-9);
  EXPECT_LT(vs_camera.rpe_trans_rmse_m, 1e-9);
  EXPECT_LT(vs_camera.rpe_rot_rmse_deg, 1e-4);
  EXPECT_GT(vs_marker.rpe_rot_rmse_deg, 5.0);      // the camera/marker frames differ by a large rotation
  EXPECT_GT(vs_marker.rpe_trans_rmse_m, 0.05);
  EXPECT_LT(vs_marker.ate_rmse_m, 0.03);          // only the ~2 cm marker-camera lever arm shows up in ATE
}

}  // namespace
}  // namespace amos::eval
