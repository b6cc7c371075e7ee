// `run --dense`: the outputs that matter are on disk before the optional stages (the dense map's final fusion and
// files, report.html) start, and an optional stage never costs them: a SIGKILL during the final fusion, a floor
// plan that cannot be written, a full disk (a file size limit: writes past it fail with EFBIG, as on a full disk)
// and a Ctrl-C during the fusion, which is answered at once.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.h"

namespace amos::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kFusionStarted = "final fusion started";

bool stagesContains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// tum3.yaml with a fine dense map (1 cm voxels at full resolution): a final fusion of a second or more, long
// enough to be interrupted, and a mesh and cloud of about 20 MB each, far above the full disk's limit. (5 mm
// voxels would prove the same with 160 MB files and four times as long.)
fs::path fineDenseConfig() {
  const fs::path config = testOutputDir("optional_stages", "config") += ".yaml";
  std::ofstream(config) << readFile(std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml")
                        << "\nDense.voxelSize: 0.01\nDense.truncation: 0.04\nDense.scale: 1.0\n";
  return config;
}

// A fine dense map (fineDenseConfig) unless `config` is given.
std::vector<std::string> denseRun(const fs::path& out, std::vector<std::string> more = {}, std::string config = {}) {
  if (config.empty()) config = fineDenseConfig().string();
  std::vector<std::string> args = {"run",    "--sequence", syntheticSequence("walking_xyz", 40), "--config",
                                   config, "--mode", "none", "--dense",
                                   "--deterministic", "--output", out.string(), "--save-map",
                                   out.string() + ".map"};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

void expectMainOutputs(const fs::path& out) {
  for (const char* name : {"trajectory.txt", "keyframes.txt", "map.ply", "stats.json", "settings_used.yaml"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  EXPECT_TRUE(fs::is_regular_file(out.string() + ".map"));
}

nlohmann::json stats(const fs::path& out) { return nlohmann::json::parse(readFile(out / "stats.json")); }

void expectNoPartialFiles(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_FALSE(stagesContains(e.path().filename().string(), "partial")) << e.path();
}

TEST(RunOptionalStages, SigkillDuringTheFinalFusionLeavesTheMainOutputs) {
  const fs::path out = testOutputDir("optional_stages", "sigkill");
  bool killed = false;
  const Finished f = runChild(denseRun(out), out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (!killed && stagesContains(line, kFusionStarted)) killed = kill(pid, SIGKILL) == 0;
  });
  ASSERT_TRUE(killed) << f.err;
  ASSERT_TRUE(WIFSIGNALED(f.status));
  expectMainOutputs(out);
  EXPECT_EQ(stats(out)["end"]["status"], "complete");
  EXPECT_FALSE(fs::exists(out / "mesh.ply"));
}

TEST(RunOptionalStages, AFloorPlanThatCannotBeWrittenIsAWarningUnlessAskedToFail) {
  // The shipped dense settings: this failure needs no long fusion nor large files.
  const std::string config = std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml";
  for (const bool fail_on_optional : {false, true}) {
    const fs::path out = testOutputDir("optional_stages", fail_on_optional ? "floor_fail" : "floor_warn");
    const Finished f = runChild(denseRun(out,
                                         fail_on_optional ? std::vector<std::string>{"--fail-on-optional"}
                                                          : std::vector<std::string>{},
                                         config),
                                out.string() + ".stdout", [&](const std::string& line, pid_t) {
                                  // In the way of the floor plan's image, once the folder is the run's.
                                  if (stagesContains(line, kFusionStarted)) fs::create_directories(out / "occupancy.pgm");
                                });
    ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
    EXPECT_EQ(WEXITSTATUS(f.status), fail_on_optional ? 1 : 0) << f.err;
    expectMainOutputs(out);
    for (const char* name : {"mesh.ply", "cloud.ply", "removed_points.ply"})
      EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
    const nlohmann::json s = stats(out);
    EXPECT_EQ(s["end"]["status"], "complete");
    EXPECT_EQ(s["optional_stages"]["dense"]["status"], "failed") << s["optional_stages"];
    EXPECT_TRUE(stagesContains(s["optional_stages"]["dense"]["reason"].get<std::string>(), "occupancy"));
    EXPECT_EQ(s["dense"]["files"]["mesh.ply"], "written");
    EXPECT_TRUE(stagesContains(f.out, "optional stage dense: failed")) << f.out;
  }
}

// amos-slam in a child whose files may not grow past `limit` bytes (SIGXFSZ ignored: the write fails with EFBIG).
Finished runWithFileSizeLimit(const std::vector<std::string>& args, rlim_t limit, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit fsize{limit, limit};
    setrlimit(RLIMIT_FSIZE, &fsize);
    std::vector<char*> argv{const_cast<char*>(AMOS_SLAM_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(AMOS_SLAM_EXE, argv.data());
    _exit(127);
  }
  Finished f;
  waitpid(pid, &f.status, 0);
  f.err = readFile(log);
  return f;
}

TEST(RunOptionalStages, AFullDiskLeavesNoTruncatedFileUnderAFinalName) {
  const fs::path out = testOutputDir("optional_stages", "full_disk");
  // The main outputs of 40 frames are far below 4 MB; the dense map's mesh and cloud at 5 mm are far above.
  const Finished f = runWithFileSizeLimit(denseRun(out), 4 << 20, out.string() + ".log");
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  expectMainOutputs(out);
  EXPECT_FALSE(fs::exists(out / "mesh.ply")) << fs::file_size(out / "mesh.ply") << " bytes under the final name";
  EXPECT_FALSE(fs::exists(out / "cloud.ply"));
  expectNoPartialFiles(out);
  const nlohmann::json s = stats(out);
  EXPECT_EQ(s["optional_stages"]["dense"]["status"], "failed");
  EXPECT_TRUE(stagesContains(s["optional_stages"]["dense"]["reason"].get<std::string>(), "mesh.ply"));
}

TEST(RunOptionalStages, ASignalDuringTheFinalFusionIsAnsweredAtOnceAndStopsIt) {
  const fs::path out = testOutputDir("optional_stages", "sigint");
  Clock::time_point sent{}, answered{};
  const Finished f = runChild(denseRun(out), out.string() + ".stdout", [&](const std::string& line, pid_t pid) {
    if (sent == Clock::time_point{} && stagesContains(line, kFusionStarted)) {
      sent = Clock::now();
      kill(pid, SIGINT);
    }
    if (answered == Clock::time_point{} && stagesContains(line, "interrupted during dense fusion")) answered = Clock::now();
  });
  ASSERT_NE(sent, Clock::time_point{}) << f.err;
  ASSERT_NE(answered, Clock::time_point{}) << f.err;
  EXPECT_LT(std::chrono::duration<double>(answered - sent).count(), 1.0);
  EXPECT_TRUE(stagesContains(f.err, "trajectory.txt, keyframes.txt, map.ply, stats.json")) << f.err;
  ASSERT_TRUE(WIFEXITED(f.status)) << f.err;
  EXPECT_EQ(WEXITSTATUS(f.status), 130);
  expectMainOutputs(out);
  EXPECT_EQ(stats(out)["optional_stages"]["dense"]["status"], "interrupted");
  EXPECT_FALSE(fs::exists(out / "mesh.ply"));
}

}  // namespace
}  // namespace amos::app
