// `run --dense` and `eval-mesh` find the dense map's module (libamos_dense_plugin.so, src/amos/run/dense_plugin.h)
// beside the program and load it then: an error the module raises reaches the program as it did when the dense
// map was linked in (a core::Error thrown in the module, caught in the program), and a program without the module
// runs everything else and says where it looked for it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>

#include "child_process.h"

namespace amos::app {
namespace {

namespace fs = std::filesystem;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The output of a shell command (stdout and stderr) and its exit status.
std::pair<int, std::string> shell(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  std::string text;
  if (pipe == nullptr) return {-1, text};
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

// Dense.maskMargin at 300 px passes the settings' own check but not the dense mapper's, which knows the image
// (640 x 480 here) only when the run starts: in the module.
TEST(DensePlugin, ASettingTheModuleRejectsEndsTheRunWithTheSettingsError) {
  const fs::path out = testOutputDir("dense_plugin", "bad_margin");
  const fs::path config = out.string() + ".yaml";
  const std::string tum3 = readFile(std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml");
  std::ofstream(config) << tum3 << "\nDense.maskMargin: 300\n";
  const int line = static_cast<int>(std::count(tum3.begin(), tum3.end(), '\n')) + 2;
  const Finished f = runChild({"run", "--sequence", syntheticSequence("walking_xyz", 30), "--config", config.string(),
                               "--mode", "none", "--dense", "--deterministic", "--output", out.string()},
                              out.string() + ".stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  EXPECT_EQ(WEXITSTATUS(f.status), 1) << f.err;
  EXPECT_TRUE(contains(f.err, "error: " + config.string() + ":" + std::to_string(line) +
                                  ": Dense.maskMargin must be below half the image (240 px of 640 x 480), got 300"))
      << f.err;
}

TEST(DensePlugin, WithoutTheModuleOnlyTheDenseCommandsFailAndSayWhereTheyLooked) {
  const fs::path dir = testOutputDir("dense_plugin", "alone");
  fs::create_directories(dir / "bin");
  const fs::path program = dir / "bin" / "amos-slam";
  fs::copy_file(AMOS_SLAM_EXE, program);
  const auto [version_status, version] = shell("'" + program.string() + "' --version");
  EXPECT_EQ(version_status, 0) << version;
  std::ofstream(dir / "mesh.ply") << "ply\n";  // eval-mesh's arguments must exist; the module is looked for first
  const auto [status, text] = shell("'" + program.string() + "' eval-mesh --mesh '" + (dir / "mesh.ply").string() +
                                    "' --sequence '" + dir.string() + "'");
  EXPECT_EQ(status, 1) << text;
  EXPECT_TRUE(contains(text, (dir / "bin" / "libamos_dense_plugin.so").string())) << text;
  EXPECT_TRUE(contains(text, (dir / "lib" / "amos" / "libamos_dense_plugin.so").string())) << text;
}

}  // namespace
}  // namespace amos::app
