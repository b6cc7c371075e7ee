// settings_used.yaml as a user relies on it: a run writes the settings it ran with beside stats.json (the command
// line on top, --mode as Dynamic.mode), and `run --config <that file>` with the same other flags repeats the run:
// with --deterministic the trajectory is bit-identical.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <string>
#include <vector>

#include "amos/synth/sequence.h"
#include "child_process.h"

namespace amos::app {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> deterministicRun(const std::string& sequence, const std::string& config,
                                          const fs::path& output) {
  return {"run",           "--sequence", sequence, "--config", config, "--mode", "full", "--models", AMOS_MODELS_DIR,
          "--deterministic", "--output",   output.string()};
}

TEST(RunSettingsUsed, RepeatsTheRunBitIdentically) {
  const std::string sequence = syntheticSequence("walking_xyz", 30);
  const fs::path first = testOutputDir("settings_used", "first");
  const fs::path again = testOutputDir("settings_used", "again");
  Finished f = runChild(deterministicRun(sequence, std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml", first),
                        first.string() + ".stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  ASSERT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  const std::string used = readFile(first / "settings_used.yaml");
  EXPECT_EQ(used.rfind("%YAML:1.0\n", 0), 0u) << used;
  EXPECT_NE(used.find("# command line: "), std::string::npos) << used;
  EXPECT_NE(used.find("--deterministic"), std::string::npos) << used;
  EXPECT_NE(used.find("\nDynamic.mode: full\n"), std::string::npos) << used;
  EXPECT_NE(used.find("\nCamera.fx: 535.4\n"), std::string::npos) << used;

  f = runChild(deterministicRun(sequence, (first / "settings_used.yaml").string(), again),
               again.string() + ".stdout");
  ASSERT_TRUE(WIFEXITED(f.status));
  ASSERT_EQ(WEXITSTATUS(f.status), 0) << f.err;
  EXPECT_EQ(f.err.find("unknown key"), std::string::npos) << f.err;
  const std::string trajectory = readFile(first / "trajectory.txt");
  EXPECT_GT(trajectory.size(), 100u);
  EXPECT_EQ(readFile(again / "trajectory.txt"), trajectory);
  // The repeat's own settings_used.yaml holds the same settings (only its comments differ).
  auto keys = [](const std::string& text) { return text.substr(text.find("\n\n")); };
  EXPECT_EQ(keys(readFile(again / "settings_used.yaml")), keys(used));
}

}  // namespace
}  // namespace amos::app
