#include "amos/run/trajectory_evaluation.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace amos::run {
namespace {

namespace fs = std::filesystem;

std::vector<io::StampedPose> line(int n, double step) {
  std::vector<io::StampedPose> poses;
  for (int i = 0; i < n; ++i) {
    io::StampedPose p;
    p.timestamp = 100.0 + i / 30.0;
    p.T_wc.translation() = Eigen::Vector3d(step * i, 0.01 * i * i, 0);
    poses.push_back(p);
  }
  return poses;
}

// Driven alone: a trajectory equal to the ground truth has ATE 0; the ground truth is offered to observers.
TEST(TrajectoryEvaluation, EvaluatesTheTrajectoryAgainstTheGroundTruth) {
  const fs::path dir = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "trajectory_evaluation";
  fs::create_directories(dir);
  const std::string gt_file = (dir / "groundtruth.txt").string();
  const std::vector<io::StampedPose> gt = line(60, 0.02);
  io::writeTumTrajectory(gt_file, gt);
  TrajectoryEvaluation evaluation(gt_file, config::GroundTruthFormat::kTum);
  EXPECT_EQ(evaluation.groundTruthForObservers().size(), gt.size());
  report::RunInfo info;
  evaluation.addToInfo(gt, info);
  ASSERT_TRUE(info.evaluation);
  EXPECT_NEAR(info.evaluation->ate_rmse_m, 0.0, 1e-9);
  EXPECT_EQ(info.evaluation->ate_pairs, gt.size());
}

// Nothing to evaluate: no ground truth, or fewer than two poses.
TEST(TrajectoryEvaluation, NothingWithoutGroundTruthOrPoses) {
  report::RunInfo info;
  TrajectoryEvaluation none("", config::GroundTruthFormat::kTum);
  EXPECT_TRUE(none.groundTruthForObservers().empty());
  none.addToInfo(line(10, 0.02), info);
  EXPECT_FALSE(info.evaluation);
  TrajectoryEvaluation missing("/nonexistent/groundtruth.txt", config::GroundTruthFormat::kTum);
  EXPECT_TRUE(missing.groundTruthForObservers().empty());
  missing.addToInfo(line(1, 0.02), info);
  EXPECT_FALSE(info.evaluation);
}

}  // namespace
}  // namespace amos::run
