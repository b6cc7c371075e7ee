#include "amos/io/line_log.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "amos/core/error.h"
#include "amos/io/trajectory.h"
#include "amos/testing/scratch_dir.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;

std::string fileText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// What is appended is in the file as soon as append() returns, with no close: a process killed by SIGKILL right
// after leaves every line, and the trajectory reader takes the file.
TEST(LineLog, LinesSurviveAProcessKilledWithoutWarning) {
  const fs::path path = testing::scratchDirForThisTest("amos_line_log_") / "trajectory_live.txt";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    LineLog log(path.string(), kTumTrajectoryHeader);
    for (int i = 0; i < 3; ++i) {
      StampedPose pose;
      pose.timestamp = 1.0 + i;
      pose.T_wc.translation() = Eigen::Vector3d(i, 0, 0);
      log.append(formatTumPose(pose));
    }
    raise(SIGKILL);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  const std::vector<StampedPose> poses = readTumTrajectory(path.string());
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_DOUBLE_EQ(poses[2].timestamp, 3.0);
  EXPECT_DOUBLE_EQ(poses[2].T_wc.translation().x(), 2.0);
}

TEST(LineLog, AFileThatCannotBeCreatedIsAnErrorNamingIt) {
  const fs::path path = testing::scratchDirForThisTest("amos_line_log_") / "missing" / "frames.tsv";
  try {
    LineLog log(path.string(), "# header\n");
    FAIL() << "no error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(LineLog, TheFormatIsWriteTumTrajectorys) {
  const fs::path dir = testing::scratchDirForThisTest("amos_line_log_");
  StampedPose pose;
  pose.timestamp = 1305031102.175304;
  pose.T_wc = core::makeSE3(Eigen::Quaterniond(0.9, 0.1, -0.2, 0.3).normalized(), Eigen::Vector3d(1.5, -2, 0.25));
  writeTumTrajectory((dir / "whole.txt").string(), {pose, pose});
  {
    LineLog log((dir / "lines.txt").string(), kTumTrajectoryHeader);
    log.append(formatTumPose(pose));
    log.append(formatTumPose(pose));
  }
  EXPECT_EQ(fileText(dir / "lines.txt"), fileText(dir / "whole.txt"));
}

}  // namespace
}  // namespace amos::io
