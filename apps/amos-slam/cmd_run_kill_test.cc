// A run killed without warning (SIGKILL: no handler, no outputs written at the end) on the real Bonn crowd slice
// keeps its work: trajectory_live.txt, appended and flushed frame by frame, is a valid trajectory of the frames
// tracked before the kill, which `amos-slam eval` accepts against the sequence's ground truth.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "amos/testing/shared_data.h"
#include "child_process.h"

namespace amos::app {
namespace {

namespace fs = std::filesystem;

// Lines of a file that hold a pose (not a comment), counting only whole lines.
std::size_t poseLines(const fs::path& file) {
  const std::string text = readFile(file);
  std::size_t n = 0, start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    n += end > start && text[start] != '#';
  return n;
}

// amos-slam with `args`, stdout and stderr into files; returns its pid at once.
pid_t startChild(const std::vector<std::string>& args, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    std::vector<char*> argv{const_cast<char*>(AMOS_SLAM_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(AMOS_SLAM_EXE, argv.data());
    _exit(127);
  }
  return pid;
}

TEST(RunKilled, SigkillLeavesAValidTrajectoryOfTheFramesTracked) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  const std::string sequence = testing::dataPath("bonn_crowd_dev");
  const fs::path out = testOutputDir("killed", "bonn");
  const fs::path live = out / "trajectory_live.txt";
  const pid_t pid = startChild({"run", "--sequence", sequence, "--config",
                                std::string(AMOS_SOURCE_DIR) + "/configs/bonn.yaml", "--mode", "none", "--output",
                                out.string()},
                               out.string() + ".log");
  // Watch the flushed file grow; kill at about 100 frames (or fail after two minutes).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  std::size_t seen = 0;
  while ((seen = fs::exists(live) ? poseLines(live) : 0) < 100 && std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, WNOHANG), 0) << "the run ended before it was killed:\n"
                                                 << readFile(out.string() + ".log");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_GE(seen, 100u) << readFile(out.string() + ".log");
  // Nothing was written at the end: only the per-frame files (and the manifest) are there.
  EXPECT_FALSE(fs::exists(out / "trajectory.txt"));
  EXPECT_FALSE(fs::exists(out / "stats.json"));
  const std::size_t poses = poseLines(live);
  EXPECT_GE(poses, seen);
  EXPECT_LT(poses, 270u);
  // Every frame processed is in frames.tsv, one whole line each, the tracked ones in the trajectory.
  EXPECT_GE(poseLines(out / "frames.tsv"), poses);
  const std::string text = readFile(live);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');

  const fs::path eval_out = out.string() + ".eval";
  const Finished eval =
      runChild({"eval", "--gt", sequence + "/groundtruth.txt", "--est", live.string(), "--bonn-gt", "--json"},
               eval_out);
  ASSERT_TRUE(WIFEXITED(eval.status));
  EXPECT_EQ(WEXITSTATUS(eval.status), 0) << eval.err;
  const nlohmann::json result = nlohmann::json::parse(eval.out, nullptr, false);
  ASSERT_TRUE(result.is_object()) << eval.out;
  EXPECT_GE(result["ate_pairs"].get<std::size_t>(), poses * 9 / 10) << eval.out;
  // `none` on the crowd is plain SLAM among walking people: its error varies from run to run (0.3-0.6 m); the
  // check is that the poses are whole numbers of a room-scale trajectory, not that they are accurate.
  EXPECT_LT(result["ate_rmse_m"].get<double>(), 2.0) << eval.out;
}

}  // namespace
}  // namespace amos::app
