// `amos-slam run` as a user runs it, in a child process on a short synthetic sequence: SIGINT / SIGTERM end the
// run with its outputs and exit status 130 / 143, a second signal ends it at once, the streams are split (progress
// and warnings on stderr, the summary on stdout), and a bad --output is refused before anything runs.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <tuple>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "amos/synth/sequence.h"
#include "child_process.h"

namespace amos::app {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 40;

std::string sequence() { return syntheticSequence("static_xyz", kFrames); }

fs::path outputDir(const std::string& name) { return testOutputDir("run", name); }

std::vector<std::string> runArgs(const fs::path& output) { return app::runArgs(sequence(), "none", output); }

// Lines of a trajectory file that hold a pose.
std::size_t poses(const fs::path& trajectory) {
  std::ifstream in(trajectory);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += !line.empty() && line[0] != '#';
  return n;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void expectNoPartialFiles(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_FALSE(contains(e.path().filename().string(), ".partial")) << e.path();
}

// SIGINT / SIGTERM after the 5th frame: the run ends at the next frame boundary and writes every output for the
// frames processed so far, with exit status 128 + the signal.
void expectStoppedBy(int signal_number, const std::string& name) {
  const fs::path out = outputDir("stopped_by_" + name);
  bool sent = false;
  const Finished f = runChild(runArgs(out), out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (!sent && contains(line, "frame 5/")) {
      kill(pid, signal_number);
      sent = true;
    }
  });
  ASSERT_TRUE(sent) << f.err;
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 128 + signal_number) << f.err;
  const std::size_t n = poses(out / "trajectory.txt");
  EXPECT_GE(n, 5u);
  EXPECT_LT(n, static_cast<std::size_t>(kFrames));
  for (const char* file : {"keyframes.txt", "map.ply", "stats.json"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  const nlohmann::json stats = nlohmann::json::parse(readFile(out / "stats.json"));
  EXPECT_EQ(stats["end"]["status"], "interrupted");
  EXPECT_EQ(stats["end"]["reason"], name);
  EXPECT_EQ(stats["frames"], n);
  EXPECT_TRUE(contains(f.err, "run interrupted by " + name)) << f.err;
  EXPECT_TRUE(contains(f.out, "frames " + std::to_string(n) + " ")) << f.out;
  EXPECT_TRUE(contains(f.out, "run interrupted after")) << f.out;
  expectNoPartialFiles(out);
}

TEST(RunCommand, SigintEndsTheRunWithItsOutputsAndStatus130) { expectStoppedBy(SIGINT, "SIGINT"); }

TEST(RunCommand, SigtermEndsTheRunWithItsOutputsAndStatus143) { expectStoppedBy(SIGTERM, "SIGTERM"); }

// A second signal ends the program at once (the default action). The run is made to wait after the first one: a
// paced replay (--realtime) whose 6th frame is due a minute after the 5th, so the loop sits in the source's wait
// when SIGTERM follows SIGINT.
TEST(RunCommand, ASecondSignalEndsItAtOnce) {
  const fs::path out = outputDir("second_signal");
  const fs::path slow = outputDir("second_signal_sequence");
  fs::copy(sequence(), slow, fs::copy_options::recursive);
  std::istringstream rows(readFile(slow / "associations.txt"));
  std::ofstream associations(slow / "associations.txt");
  std::string row;
  for (int k = 0; k < 6 && std::getline(rows, row);) {
    if (row.empty() || row[0] == '#') continue;
    std::istringstream fields(row);
    double t_rgb = 0, t_depth = 0;
    std::string rgb, depth;
    fields >> t_rgb >> rgb >> t_depth >> depth;
    const double late = k == 5 ? 60.0 : 0.0;
    associations << std::fixed << t_rgb + late << " " << rgb << " " << t_depth + late << " " << depth << "\n";
    ++k;
  }
  associations.close();
  std::vector<std::string> args = runArgs(out);
  args[2] = slow.string();
  args.push_back("--realtime");
  bool sent = false;
  const auto start = std::chrono::steady_clock::now();
  const Finished f = runChild(args, out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (!sent && contains(line, "frame 5/6")) {
      kill(pid, SIGINT);
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      kill(pid, SIGTERM);
      sent = true;
    }
  });
  ASSERT_TRUE(sent) << f.err;
  ASSERT_TRUE(WIFSIGNALED(f.status)) << f.err;
  EXPECT_EQ(WTERMSIG(f.status), SIGTERM);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
  if (fs::exists(out)) expectNoPartialFiles(out);
}

// Not a terminal: one progress line per --progress-every frames on stderr, never a carriage return; stdout holds
// the summary only.
TEST(RunCommand, ProgressAndWarningsOnStderrSummaryOnStdout) {
  const fs::path out = outputDir("streams");
  std::vector<std::string> args = runArgs(out);
  args.back() = "10";  // --progress-every 10
  const Finished f = runChild(args, out.string() + ".stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_FALSE(contains(f.err, "\r"));
  EXPECT_TRUE(contains(f.err, "frame 10/40")) << f.err;
  EXPECT_TRUE(contains(f.err, "frame 40/40")) << f.err;
  EXPECT_FALSE(contains(f.err, "frame 11/40")) << f.err;
  std::istringstream lines(f.out);
  std::vector<std::string> out_lines;
  for (std::string line; std::getline(lines, line);) out_lines.push_back(line);
  ASSERT_FALSE(out_lines.empty());
  EXPECT_EQ(out_lines.front().rfind("frames 40  tracked 40", 0), 0u) << f.out;
  EXPECT_EQ(out_lines.back(), "outputs written to " + out.string());
  for (const std::string& line : out_lines) {
    EXPECT_FALSE(contains(line, "[info]") || contains(line, "[warning]") || contains(line, "frame ")) << line;
  }
}

// SIGPIPE never kills a run: with nobody reading stdout the run still ends normally and writes its outputs.
TEST(RunCommand, AClosedStdoutDoesNotKillTheRun) {
  const fs::path out = outputDir("closed_stdout");
  const Finished f = runChild(runArgs(out), fs::path());
  ASSERT_TRUE(WIFEXITED(f.status)) << "killed by signal " << WTERMSIG(f.status);
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_EQ(poses(out / "trajectory.txt"), static_cast<std::size_t>(kFrames));
}

// --output is checked before anything runs: a path under a file and a folder holding an earlier run are refused at
// once (exit 1, nothing written); --overwrite replaces the earlier run.
// Negative counts and ports beyond 65535 are refused by the parser, naming the flag (before, --first-frame -1 ran
// as frame 18446744073709551615 and --viewer-port 70000 listened on 4464).
TEST(RunCommand, NegativeOrOutOfRangeNumbersAreRefusedByTheParser) {
  const fs::path out = outputDir("bad_numbers");
  for (const auto& [flag, value, message] :
       {std::tuple<std::string, std::string, std::string>{"--first-frame", "-1", "must be a whole number, 0 or more"},
        {"--max-frames", "-5", "must be a whole number, 0 or more"},
        {"--viewer-port", "70000", "must be a port, 0 (any free one) to 65535"}}) {
    std::vector<std::string> args = runArgs(out / "run");
    args.push_back(flag);
    args.push_back(value);
    const Finished f = runChild(args, out / "stdout");
    ASSERT_TRUE(WIFEXITED(f.status));
    EXPECT_NE(WEXITSTATUS(f.status), 0) << flag;
    EXPECT_TRUE(contains(f.err, flag + ": " + message)) << f.err;
    EXPECT_FALSE(fs::exists(out / "run" / "trajectory.txt")) << flag;
  }
}

TEST(RunCommand, BadOutputIsRefusedBeforeTheRun) {
  const fs::path root = outputDir("bad_output");
  fs::create_directories(root);
  std::ofstream(root / "file") << "x";
  Finished f = runChild(runArgs(root / "file" / "run"), root / "stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 1);
  EXPECT_TRUE(contains(f.err, "'" + (root / "file").string() + "' is a file")) << f.err;
  EXPECT_TRUE(f.out.empty()) << f.out;

  fs::create_directories(root / "earlier");
  std::ofstream(root / "earlier" / "stats.json") << "{}";
  std::ofstream(root / "earlier" / "notes.txt") << "mine";
  f = runChild(runArgs(root / "earlier"), root / "stdout");
  EXPECT_EQ(WEXITSTATUS(f.status), 1);
  EXPECT_TRUE(contains(f.err, "holds an earlier run (stats.json)")) << f.err;
  EXPECT_EQ(readFile(root / "earlier" / "stats.json"), "{}");

  std::vector<std::string> args = runArgs(root / "earlier");
  args.push_back("--overwrite");
  args.push_back("--max-frames");
  args.push_back("3");
  f = runChild(args, root / "stdout");
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_EQ(poses(root / "earlier" / "trajectory.txt"), 3u);
  EXPECT_EQ(readFile(root / "earlier" / "notes.txt"), "mine");
}

}  // namespace
}  // namespace amos::app
