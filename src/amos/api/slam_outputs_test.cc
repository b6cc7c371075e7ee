// amos::Slam::writeOutputs: the files `amos-slam run` writes, by the same code, for the same frames: the same file
// names; trajectory.txt, keyframes.txt, map.ply and trajectory_live.txt byte for byte in deterministic mode;
// frames.tsv with run's columns and frames; stats.json with run's keys and the caller's description;
// settings_used.yaml the run's effective settings; run_manifest.json listing what was written.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "amos/config/settings_writer.h"
#include "amos/report/output_folder.h"
#include "amos/report/run_report.h"
#include "amos/run/sequence_run.h"
#include "amos/run/settings_sections.h"
#include "amos/sequence_folder.h"
#include "amos/slam.h"
#include "amos/synth/sequence.h"
#include "amos/testing/file_text.h"
#include "amos/testing/scratch_dir.h"
#include "amos/testing/test_inputs.h"

namespace amos {
namespace {

namespace fs = std::filesystem;

using amos::testing::kTum3;


// The settings file's keys and values, without its comment lines (which say who wrote it).
std::string withoutComments(const std::string& text) {
  std::istringstream in(text);
  std::string out, line;
  while (std::getline(in, line))
    if (line.rfind('#', 0) != 0) out += line + "\n";
  return out;
}

std::set<std::string> fileNames(const fs::path& dir) {
  std::set<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

// A TSV file's lines (its header included), each split at its tabs.
std::vector<std::vector<std::string>> tsvRows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> row;
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, '\t')) row.push_back(field);
    rows.push_back(std::move(row));
  }
  return rows;
}

std::set<std::string> keys(const nlohmann::json& object) {
  std::set<std::string> out;
  for (const auto& item : object.items()) out.insert(item.key());
  return out;
}

// frames.tsv: run's header and frames; per frame the same index, time stamp, state, inliers and keyframe flag (the
// rgb file names the frame as its caller did; frame_ms is wall time).
void expectSameFrames(const fs::path& api, const fs::path& run) {
  const auto api_rows = tsvRows(testing::fileText(api)), run_rows = tsvRows(testing::fileText(run));
  ASSERT_EQ(api_rows.size(), run_rows.size());
  ASSERT_GT(api_rows.size(), 1u);
  EXPECT_EQ(api_rows[0], run_rows[0]);  // the header: the columns' names
  for (std::size_t i = 1; i < api_rows.size(); ++i) {
    ASSERT_EQ(api_rows[i].size(), run_rows[i].size()) << "line " << i;
    for (std::size_t column : {0, 1, 3, 4, 5}) EXPECT_EQ(api_rows[i][column], run_rows[i][column]) << "line " << i;
    EXPECT_GE(std::stod(api_rows[i][6]), 0.0) << "line " << i;
  }
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
  options.live_log_dir = (dir / "run").string();
  // As cmd_run.cc: the folder with its manifest, the run (its per-frame files), the final files and the settings.
  const report::OutputFolderLock lock =
      report::prepareOutputFolder({options.live_log_dir, false, report::mainOutputNames(), seq});
  const run::SequenceRunResult run = run::runSequence(settings, options);
  report::writeRunOutputs((dir / "run").string(), run.slam(), run.info);
  config::writeSettingsFile((dir / "run" / "settings_used.yaml").string(), run::effectiveSettings(settings, options),
                            {});

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
  description.groundtruth_file = seq + "/groundtruth.txt";
  slam.writeOutputs((dir / "api").string(), description);

  std::set<std::string> run_names = fileNames(dir / "run");
  run_names.erase(report::kLockFile);  // the run's lock, held by this test
  EXPECT_EQ(fileNames(dir / "api"), run_names);
  const std::vector<std::string> names = Slam::outputNames();
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), run_names);
  for (const char* name : {"trajectory.txt", "keyframes.txt", "map.ply", "trajectory_live.txt"}) {
    const std::string expected = testing::fileText(dir / "run" / name);
    EXPECT_FALSE(expected.empty()) << name;
    EXPECT_EQ(testing::fileText(dir / "api" / name), expected) << name;
  }
  const nlohmann::json stats = nlohmann::json::parse(testing::fileText(dir / "api" / "stats.json"));
  const nlohmann::json run_stats = nlohmann::json::parse(testing::fileText(dir / "run" / "stats.json"));
  EXPECT_EQ(stats["frames"], run_stats["frames"]);
  EXPECT_EQ(stats["keyframes"], run_stats["keyframes"]);
  EXPECT_EQ(stats["mode"], "geometry");
  EXPECT_EQ(stats["sequence"], seq);
  EXPECT_EQ(stats["config"], kTum3);
  EXPECT_EQ(stats["source"]["kind"], "test");
  EXPECT_EQ(stats["source"]["delivered"], folder.size() + 2);
  EXPECT_EQ(stats["source"]["dropped"], 2);
  EXPECT_GT(stats["wall_time_s"].get<double>(), 0.0);
  // run's shape: its keys, its stages, the share of keypoints removed per frame, the depth dropouts, the evaluation
  // against the same ground truth. Aside: what run has of the sequence folder, which the Slam never sees (its
  // association file; its mover masks and the time scoring against them).
  std::set<std::string> run_keys = keys(run_stats);
  for (const char* key : {"association", "mask_accuracy", "mask_outputs_s"}) run_keys.erase(key);
  EXPECT_EQ(keys(stats), run_keys);
  EXPECT_EQ(keys(stats["stages"]), keys(run_stats["stages"]));
  EXPECT_EQ(stats["removed_keypoint_fraction"]["per_frame"].size(), folder.size());
  EXPECT_EQ(stats["depth_dropouts"], run_stats["depth_dropouts"]);
  ASSERT_TRUE(run_stats.contains("evaluation"));
  EXPECT_EQ(stats["evaluation"], run_stats["evaluation"]);
  expectSameFrames(dir / "api" / "frames.tsv", dir / "run" / "frames.tsv");
  // run_manifest.json: what was written there, as run's manifest lists it.
  const nlohmann::json manifest = nlohmann::json::parse(testing::fileText(dir / "api" / report::kManifestFile));
  const nlohmann::json run_manifest = nlohmann::json::parse(testing::fileText(dir / "run" / report::kManifestFile));
  EXPECT_EQ(manifest["outputs"], run_manifest["outputs"]);
  // settings_used.yaml: the run's effective settings (its comment lines aside), readable as settings again.
  const std::string used = testing::fileText(dir / "api" / "settings_used.yaml");
  EXPECT_EQ(withoutComments(used),
            withoutComments(config::settingsFileText(run::effectiveSettings(settings, options), {})));
  EXPECT_NO_THROW(run::loadSettings((dir / "api" / "settings_used.yaml").string()));
}

}  // namespace
}  // namespace amos
