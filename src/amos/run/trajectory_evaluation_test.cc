#include "amos/run/trajectory_evaluation.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "amos/core/log_capture.h"
#include "amos/testing/scratch_dir.h"

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
  EXPECT_FALSE(missing.usable());
  EXPECT_TRUE(missing.groundTruthForObservers().empty());
  missing.addToInfo(line(1, 0.02), info);
  EXPECT_FALSE(info.evaluation);
}

// A bad ground-truth file is found when the observer is made (before the run's first frame): a warning naming
// the file and the line, no evaluation at the end, and nothing thrown, so the run and its outputs go on.
TEST(TrajectoryEvaluation, ABadGroundTruthIsAWarningBeforeTheRun) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_bad_gt_");
  const std::string good = "1.0 0 0 0 0 0 0 1\n2.0 0.1 0 0 0 0 0 1\n";
  const struct {
    std::string name, text, where;
  } cases[] = {{"bad_first_line", "timestamp tx ty tz qx qy qz qw\n" + good, ":1:"},
               {"truncated_last_line", good + "3.0 0.2 0 0 0", ":3:"},
               {"unparsable", good + "3.0 0.2 x 0 0 0 0 1\n", ":3:"},
               {"empty", "", "is empty"}};
  for (const auto& c : cases) {
    const std::string file = (dir / (c.name + ".txt")).string();
    std::ofstream(file) << c.text;
    core::LogCapture log;
    TrajectoryEvaluation evaluation(file, config::GroundTruthFormat::kTum);
    EXPECT_FALSE(evaluation.usable()) << c.name;
    EXPECT_TRUE(evaluation.groundTruthForObservers().empty()) << c.name;
    const std::vector<std::string> lines = log.lines();
    ASSERT_EQ(lines.size(), 1u) << c.name;
    EXPECT_EQ(lines[0].rfind("warning ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(file), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find(c.where), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("the run goes on without evaluation"), std::string::npos) << lines[0];
    report::RunInfo info;
    EXPECT_NO_THROW(evaluation.addToInfo(line(10, 0.02), info));
    EXPECT_FALSE(info.evaluation) << c.name;
  }
}

// A trajectory that cannot be evaluated against a good ground truth (no stamp in common) is a warning, not an
// error that would cost the run its outputs.
TEST(TrajectoryEvaluation, AnEvaluationThatFailsIsAWarning) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_failed_eval_");
  const std::string gt_file = (dir / "groundtruth.txt").string();
  io::writeTumTrajectory(gt_file, line(60, 0.02));
  TrajectoryEvaluation evaluation(gt_file, config::GroundTruthFormat::kTum);
  std::vector<io::StampedPose> far = line(10, 0.02);
  for (io::StampedPose& p : far) p.timestamp += 1000.0;
  report::RunInfo info;
  core::LogCapture log;
  EXPECT_NO_THROW(evaluation.addToInfo(far, info));
  EXPECT_FALSE(info.evaluation);
  ASSERT_FALSE(log.lines().empty());
  EXPECT_NE(log.lines()[0].find("no evaluation against " + gt_file), std::string::npos) << log.lines()[0];
}

}  // namespace
}  // namespace amos::run
