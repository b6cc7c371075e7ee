// amos::Slam::writeOutputs: the files `amos-slam run` writes (report::writeRunOutputs and settings_used.yaml), by the
// same code, for the same frames: trajectory.txt, keyframes.txt and map.ply byte for byte in deterministic mode;
// stats.json with the caller's description; settings_used.yaml the run's effective settings.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "amos/config/settings_writer.h"
#include "amos/report/run_report.h"
#include "amos/run/sequence_run.h"
#include "amos/run/settings_sections.h"
#include "amos/sequence_folder.h"
#include "amos/slam.h"
#include "amos/synth/sequence.h"
#include "amos/testing/scratch_dir.h"

namespace amos {
namespace {

namespace fs = std::filesystem;

const std::string kTum3 = std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml";

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The settings file's keys and values, without its comment lines (which say who wrote it).
std::string withoutComments(const std::string& text) {
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line))
    if (line.rfind('#', 0) != 0) out += line + "\n";
  return out;
}

TEST(SlamOutputs, WritesRunsFilesByteForByte) {
  const std::string seq = synth::cachedSequence(
      (fs::path(AMOS_BINARY_DIR) / "test_outputs" / "api_sequences").string(), "walking_xyz", 1, 30);
  const fs::path dir = testing::scratchDirForThisTest("amos_api_outputs_");
  // What `amos-slam run --mode geometry --deterministic` writes (cmd_run.cc: report::writeRunOutputs).
  const config::Settings settings = run::loadSettings(kTum3);
  run::SequenceRunOptions options;
  options.sequence_dir = seq;
  options.mode = "geometry";
  options.deterministic = true;
  const run::SequenceRunResult run = run::runSequence(settings, options);
  report::writeRunOutputs((dir / "run").string(), run.slam(), run.info);

  Slam slam(kTum3, Mode::kGeometry, /*deterministic=*/true);
  const SequenceFolder folder(seq);
  for (std::size_t i = 0; i < folder.size(); ++i) {
    const RgbdImages f = folder.read(i);
    slam.track(f.bgr, f.depth, f.timestamp);
  }
  slam.finish();
  RunDescription description;
  description.sequence = seq;
  description.source_kind = "test";
  description.delivered = folder.size() + 2;
  description.dropped = 2;
  slam.writeOutputs((dir / "api").string(), description);

  for (const std::string name : Slam::outputNames()) EXPECT_TRUE(fs::exists(dir / "api" / name)) << name;
  for (const char* name : {"trajectory.txt", "keyframes.txt", "map.ply"}) {
    const std::string expected = readFile(dir / "run" / name);
    EXPECT_FALSE(expected.empty()) << name;
    EXPECT_EQ(readFile(dir / "api" / name), expected) << name;
  }
  const nlohmann::json stats = nlohmann::json::parse(readFile(dir / "api" / "stats.json"));
  const nlohmann::json run_stats = nlohmann::json::parse(readFile(dir / "run" / "stats.json"));
  EXPECT_EQ(stats["frames"], run_stats["frames"]);
  EXPECT_EQ(stats["keyframes"], run_stats["keyframes"]);
  EXPECT_EQ(stats["mode"], "geometry");
  EXPECT_EQ(stats["sequence"], seq);
  EXPECT_EQ(stats["config"], kTum3);
  EXPECT_EQ(stats["source"]["kind"], "test");
  EXPECT_EQ(stats["source"]["delivered"], folder.size() + 2);
  EXPECT_EQ(stats["source"]["dropped"], 2);
  EXPECT_GT(stats["wall_time_s"].get<double>(), 0.0);
  // settings_used.yaml: the run's effective settings (its comment lines aside), readable as settings again.
  const std::string used = readFile(dir / "api" / "settings_used.yaml");
  EXPECT_EQ(withoutComments(used),
            withoutComments(config::settingsFileText(run::effectiveSettings(settings, options), {})));
  EXPECT_NO_THROW(run::loadSettings((dir / "api" / "settings_used.yaml").string()));
}

}  // namespace
}  // namespace amos
