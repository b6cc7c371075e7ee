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

std::vector<std::string> noneRunArgs(const fs::path& output) { return app::runArgs(sequence(), "none", output); }

// Lines of a trajectory file that hold a pose.
std::size_t poses(const fs::path& trajectory) {
  std::ifstream in(trajectory);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += !line.empty() && line[0] != '#';
  return n;
}

bool runContains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void runExpectNoPartialFiles(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_FALSE(runContains(e.path().filename().string(), ".partial")) << e.path();
}

// SIGINT / SIGTERM after the 5th frame: the run ends at the next frame boundary and writes every output for the
// frames processed so far, with exit status 128 + the signal.
void expectStoppedBy(int signal_number, const std::string& name) {
  const fs::path out = outputDir("stopped_by_" + name);
  bool sent = false;
  const Finished f = runChild(noneRunArgs(out), out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (!sent && runContains(line, "frame 5/")) {
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
  EXPECT_TRUE(runContains(f.err, "run interrupted by " + name)) << f.err;
  EXPECT_TRUE(runContains(f.out, "frames " + std::to_string(n) + " ")) << f.out;
  EXPECT_TRUE(runContains(f.out, "run interrupted after")) << f.out;
  runExpectNoPartialFiles(out);
}

TEST(RunCommand, SigintEndsTheRunWithItsOutputsAndStatus130) { expectStoppedBy(SIGINT, "SIGINT"); }

TEST(RunCommand, SigtermEndsTheRunWithItsOutputsAndStatus143) { expectStoppedBy(SIGTERM, "SIGTERM"); }

// A copy of the test sequence, its first six frames, whose 6th frame comes `gap_s` seconds after the 5th.
fs::path sequenceWithAGap(const std::string& name, double gap_s) {
  const fs::path slow = outputDir(name);
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
    const double late = k == 5 ? gap_s : 0.0;
    associations << std::fixed << t_rgb + late << " " << rgb << " " << t_depth + late << " " << depth << "\n";
    ++k;
  }
  return slow;
}

// Ctrl-C is served at once by a --realtime replay waiting for a frame due ten minutes later (before, the replay sat
// out the gap: 11.5 minutes on a Bonn sequence). The run ends with its outputs and status 130.
TEST(RunCommand, SigintEndsARealtimeRunWaitingOutAGapAtOnce) {
  const fs::path out = outputDir("gap_sigint");
  std::vector<std::string> args = noneRunArgs(out);
  args[2] = sequenceWithAGap("gap_sigint_sequence", 600.0).string();
  args.push_back("--realtime");
  bool sent = false;
  std::chrono::steady_clock::time_point sent_at;
  const Finished f = runChild(args, out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (!sent && runContains(line, "frame 5/6")) {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the loop waits for the 6th frame by then
      kill(pid, SIGINT);
      sent_at = std::chrono::steady_clock::now();
      sent = true;
    }
  });
  ASSERT_TRUE(sent) << f.err;
  EXPECT_LT(std::chrono::steady_clock::now() - sent_at, std::chrono::seconds(20));
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 130) << f.err;
  // --realtime drops a frame that arrives while SLAM is busy, so a loaded machine may track fewer than five.
  const std::size_t tracked = poses(out / "trajectory.txt");
  EXPECT_GE(tracked, 1u);
  EXPECT_LE(tracked, 5u);
  EXPECT_EQ(poses(out / "trajectory_live.txt"), tracked);
  runExpectNoPartialFiles(out);
}

// A second signal ends the program at once (the default action), with one line on stderr saying that what is on
// disk stays valid; the per-frame trajectory is whole.
TEST(RunCommand, ASecondSignalEndsItAtOnceAndSaysTheFilesStayValid) {
  const fs::path out = outputDir("second_signal");
  bool sent = false;
  const auto start = std::chrono::steady_clock::now();
  const Finished f = runChild(noneRunArgs(out), out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (!sent && runContains(line, "frame 5/")) {
      kill(pid, SIGINT);
      kill(pid, SIGTERM);
      sent = true;
    }
  });
  ASSERT_TRUE(sent) << f.err;
  ASSERT_TRUE(WIFSIGNALED(f.status)) << f.err;
  EXPECT_TRUE(WTERMSIG(f.status) == SIGTERM || WTERMSIG(f.status) == SIGINT) << WTERMSIG(f.status);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
  EXPECT_TRUE(runContains(f.err, "second signal, ending at once; what is on disk in " + out.string() + " stays valid"))
      << f.err;
  EXPECT_GE(poses(out / "trajectory_live.txt"), 5u);
  const std::string live = readFile(out / "trajectory_live.txt");
  EXPECT_EQ(live.back(), '\n');
}

// Not a terminal: one progress line per --progress-every frames on stderr, never a carriage return; stdout holds
// the summary only.
TEST(RunCommand, ProgressAndWarningsOnStderrSummaryOnStdout) {
  const fs::path out = outputDir("streams");
  std::vector<std::string> args = noneRunArgs(out);
  args.back() = "10";  // --progress-every 10
  const Finished f = runChild(args, out.string() + ".stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_FALSE(runContains(f.err, "\r"));
  EXPECT_TRUE(runContains(f.err, "frame 10/40")) << f.err;
  EXPECT_TRUE(runContains(f.err, "frame 40/40")) << f.err;
  EXPECT_FALSE(runContains(f.err, "frame 11/40")) << f.err;
  std::istringstream lines(f.out);
  std::vector<std::string> out_lines;
  for (std::string line; std::getline(lines, line);) out_lines.push_back(line);
  ASSERT_FALSE(out_lines.empty());
  EXPECT_EQ(out_lines.front().rfind("frames 40  tracked 40", 0), 0u) << f.out;
  EXPECT_EQ(out_lines.back(), "outputs written to " + out.string());
  for (const std::string& line : out_lines) {
    EXPECT_FALSE(runContains(line, "[info]") || runContains(line, "[warning]") || runContains(line, "frame ")) << line;
  }
}

// SIGPIPE never kills a run: with nobody reading stdout the run still ends normally and writes its outputs.
TEST(RunCommand, AClosedStdoutDoesNotKillTheRun) {
  const fs::path out = outputDir("closed_stdout");
  const Finished f = runChild(noneRunArgs(out), fs::path());
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
    std::vector<std::string> args = noneRunArgs(out / "run");
    args.push_back(flag);
    args.push_back(value);
    const Finished f = runChild(args, out / "stdout");
    ASSERT_TRUE(WIFEXITED(f.status));
    EXPECT_NE(WEXITSTATUS(f.status), 0) << flag;
    EXPECT_TRUE(runContains(f.err, flag + ": " + message)) << f.err;
    EXPECT_FALSE(fs::exists(out / "run" / "trajectory.txt")) << flag;
  }
}

// A folder's ground truth is its groundtruth.txt: --groundtruth-topic (bags only, docs/ros.md) is refused before
// the run.
TEST(RunCommand, AGroundTruthTopicOnAFolderIsRefused) {
  const fs::path out = outputDir("groundtruth_topic");
  std::vector<std::string> args = noneRunArgs(out / "run");
  args.insert(args.end(), {"--groundtruth-topic", "/tf"});
  const Finished f = runChild(args, out / "stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_NE(WEXITSTATUS(f.status), 0);
  EXPECT_TRUE(runContains(f.err, "run --groundtruth-topic /tf: only for --sequence X.bag")) << f.err;
  EXPECT_FALSE(fs::exists(out / "run" / "trajectory.txt"));
}

TEST(RunCommand, BadOutputIsRefusedBeforeTheRun) {
  const fs::path root = outputDir("bad_output");
  fs::create_directories(root);
  std::ofstream(root / "file") << "x";
  Finished f = runChild(noneRunArgs(root / "file" / "run"), root / "stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 1);
  EXPECT_TRUE(runContains(f.err, "'" + (root / "file").string() + "' is a file")) << f.err;
  EXPECT_TRUE(f.out.empty()) << f.out;

  // Files no run manifest lists are never replaced, with --overwrite neither.
  fs::create_directories(root / "foreign");
  std::ofstream(root / "foreign" / "stats.json") << "{}";
  for (const bool overwrite : {false, true}) {
    std::vector<std::string> args = noneRunArgs(root / "foreign");
    if (overwrite) args.push_back("--overwrite");
    f = runChild(args, root / "stdout");
    EXPECT_EQ(WEXITSTATUS(f.status), 1);
    EXPECT_TRUE(runContains(f.err, overwrite ? "has no run manifest (run_manifest.json)"
                                          : "holds stats.json, which no run manifest (run_manifest.json) lists"))
        << f.err;
    EXPECT_TRUE(runContains(f.err, "away")) << f.err;  // says what to do: move them away
    EXPECT_EQ(readFile(root / "foreign" / "stats.json"), "{}");
  }

  // An earlier run (its manifest) is refused without --overwrite, replaced with it; other files stay.
  std::vector<std::string> args = noneRunArgs(root / "earlier");
  args.push_back("--max-frames");
  args.push_back("3");
  f = runChild(args, root / "stdout");
  ASSERT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  std::ofstream(root / "earlier" / "notes.txt") << "mine";
  f = runChild(args, root / "stdout");
  EXPECT_EQ(WEXITSTATUS(f.status), 1);
  EXPECT_TRUE(runContains(f.err, "holds an earlier run (trajectory_live.txt, frames.tsv, trajectory.txt")) << f.err;
  args.back() = "4";
  args.push_back("--overwrite");
  f = runChild(args, root / "stdout");
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_EQ(poses(root / "earlier" / "trajectory.txt"), 4u);
  EXPECT_EQ(readFile(root / "earlier" / "notes.txt"), "mine");
}

// Inputs are never written: --output, --record and --save-map inside the sequence folder (also through a symlink)
// are refused before anything runs, and nothing is created there.
TEST(RunCommand, OutputsInsideTheInputAreRefused) {
  const fs::path root = outputDir("inside_input");
  const fs::path input = root / "sequence";
  fs::create_directories(root);
  fs::copy(sequence(), input, fs::copy_options::recursive);
  fs::create_directory_symlink(input, root / "link");
  std::size_t entries = 0;
  for (auto it = fs::recursive_directory_iterator(input); it != fs::recursive_directory_iterator(); ++it) ++entries;
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--output", (input / "out").string()}, "--output '" + (input / "out").string() + "' lies inside"},
      {{"--output", input.string()}, "--output '" + input.string() + "' is the input"},
      {{"--output", (root / "link" / "out").string()}, "lies inside the input sequence folder"},
      {{"--output", (root / "out").string(), "--record", (root / "link" / "rec").string()}, "--record '"},
      {{"--output", (root / "out2").string(), "--save-map", (input / "map.bin").string()}, "--save-map '"}};
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args = {"run", "--sequence", input.string(), "--config",
                                     std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml", "--mode", "none"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Finished f = runChild(args, root / "stdout");
    ASSERT_TRUE(WIFEXITED(f.status));
    EXPECT_EQ(WEXITSTATUS(f.status), 1) << extra[1];
    EXPECT_TRUE(runContains(f.err, message)) << f.err;
    EXPECT_TRUE(runContains(f.err, "a run never writes into its input")) << f.err;
  }
  std::size_t after = 0;
  for (auto it = fs::recursive_directory_iterator(input); it != fs::recursive_directory_iterator(); ++it) ++after;
  EXPECT_EQ(after, entries);
}

// --save-map is checked before the first frame: a path whose folder does not exist is refused at once (before,
// the whole run went and then the map was lost).
TEST(RunCommand, ABadSaveMapPathIsRefusedBeforeTheRun) {
  const fs::path out = outputDir("bad_save_map");
  std::vector<std::string> args = noneRunArgs(out);
  args.push_back("--save-map");
  args.push_back((out.parent_path() / "no_such_folder" / "map.bin").string());
  const Finished f = runChild(args, out.string() + ".stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 1);
  EXPECT_TRUE(runContains(f.err, "does not exist")) << f.err;
  EXPECT_FALSE(runContains(f.err, "frame 1/")) << f.err;
  EXPECT_FALSE(fs::exists(out / "trajectory.txt"));
}

// One run per output folder: a second run on a folder in use is refused at once, naming the first one's PID.
TEST(RunCommand, ASecondRunOnTheSameOutputIsRefusedNamingThePid) {
  const fs::path out = outputDir("busy");
  std::vector<std::string> first = noneRunArgs(out);
  first[2] = sequenceWithAGap("busy_sequence", 600.0).string();
  first.push_back("--realtime");
  Finished second;
  pid_t first_pid = 0;
  const Finished f = runChild(first, out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (first_pid == 0 && runContains(line, "frame 5/6")) {  // waiting ten minutes for the 6th frame
      first_pid = pid;
      second = runChild(noneRunArgs(out), out.string() + ".second");
      kill(pid, SIGINT);
    }
  });
  ASSERT_NE(first_pid, 0) << f.err;
  ASSERT_TRUE(WIFEXITED(second.status));
  EXPECT_EQ(WEXITSTATUS(second.status), 1);
  EXPECT_TRUE(runContains(second.err, "is in use by another run (PID " + std::to_string(first_pid) + ",")) << second.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 130) << f.err;
  // The first run's outputs, untouched by the second (--realtime may drop a frame on a loaded machine).
  EXPECT_GE(poses(out / "trajectory.txt"), 1u);
  EXPECT_EQ(poses(out / "trajectory.txt"), poses(out / "trajectory_live.txt"));
  EXPECT_FALSE(fs::exists(out / ".amos-run.lock"));
}

// A ground truth that cannot be read is a warning naming the file and the line, before the first frame; the run
// goes on without evaluation and exits 0 with all its outputs.
TEST(RunCommand, ABadGroundTruthIsAWarningAndTheRunGoesOn) {
  const fs::path root = outputDir("bad_gt");
  const fs::path input = root / "sequence";
  fs::create_directories(root);
  fs::copy(sequence(), input, fs::copy_options::recursive);
  const std::string gt = readFile(input / "groundtruth.txt");
  std::ofstream(input / "groundtruth.txt") << gt.substr(0, gt.size() - 20);  // the last line cut short
  std::vector<std::string> args = noneRunArgs(root / "out");
  args[2] = input.string();
  const Finished f = runChild(args, root / "stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  const std::size_t warning = f.err.find((input / "groundtruth.txt").string() + ":");
  ASSERT_NE(warning, std::string::npos) << f.err;
  EXPECT_LT(warning, f.err.find("frame 1/")) << f.err;
  EXPECT_TRUE(runContains(f.err, "the run goes on without evaluation")) << f.err;
  EXPECT_EQ(poses(root / "out" / "trajectory.txt"), static_cast<std::size_t>(kFrames));
  for (const char* file : {"keyframes.txt", "map.ply", "stats.json", "settings_used.yaml"})
    EXPECT_TRUE(fs::exists(root / "out" / file)) << file;
  EXPECT_FALSE(nlohmann::json::parse(readFile(root / "out" / "stats.json")).contains("evaluation"));
}

// A run in which every frame was skipped fails (exit 1, saying so) instead of succeeding with nothing.
TEST(RunCommand, ARunWithEveryFrameSkippedFails) {
  const fs::path root = outputDir("all_skipped");
  const fs::path input = root / "sequence";
  fs::create_directories(root);
  fs::copy(sequence(), input, fs::copy_options::recursive);
  for (const auto& e : fs::directory_iterator(input / "rgb")) fs::resize_file(e.path(), 100);
  std::vector<std::string> args = noneRunArgs(root / "out");
  args[2] = input.string();
  const Finished f = runChild(args, root / "stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 1) << f.err;
  EXPECT_TRUE(runContains(f.err, "was skipped (unreadable 40): nothing was tracked")) << f.err;
  EXPECT_TRUE(fs::exists(root / "out" / "stats.json"));
}

}  // namespace
}  // namespace amos::app
