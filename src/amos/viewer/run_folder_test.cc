#include "amos/viewer/run_folder.h"

#include <gtest/gtest.h>

#include <fstream>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"
#include "amos/viewer/test_run_folder.h"

namespace amos::viewer {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// A run folder inside a parent that also holds a file the viewer must never hand out.
fs::path makeRun() {
  const fs::path parent = amos::testing::scratchDirForThisTest("viewer_run_folder_");
  const fs::path run = parent / "run";
  write(run / "trajectory.txt", "1.0 0 0 0 0 0 0 1\n2.0 0.1 0 0 0 0 0 1\n");
  write(run / "keyframes.txt", "1.0 0 0 0 0 0 0 1\n");
  write(run / "map.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n0 0 1\n0.5 0 2\n");
  write(run / "stats.json", R"({"frames": 2, "mode": "full", "sequence": "s"})");
  write(run / "overlays" / "1.000000.png", "png");
  write(parent / "secret.txt", "not for the browser");
  return run;
}

TEST(RunFilePath, ServesOnlyFilesInsideTheRunFolder) {
  const fs::path run = makeRun();
  EXPECT_TRUE(runFilePath(run, "stats.json"));
  EXPECT_TRUE(runFilePath(run, "overlays/1.000000.png"));
  for (const std::string& bad : std::vector<std::string>{"../secret.txt", "overlays/../../secret.txt", "/etc/passwd", "./stats.json",
                                "overlays/../stats.json", "", "overlays", "missing.txt", "..\\secret.txt",
                                std::string("stats.json\0x", 12), "//etc/passwd"})
    EXPECT_FALSE(runFilePath(run, bad)) << bad;
}

TEST(RunFilePath, RefusesASymbolicLinkOutOfTheFolder) {
  const fs::path run = makeRun();
  fs::create_symlink(run.parent_path() / "secret.txt", run / "link.txt");
  EXPECT_FALSE(runFilePath(run, "link.txt"));
}

TEST(LoadRunFolder, LoadsTrajectoryKeyframesMapStatsAndOverlays) {
  const fs::path run = makeRun();
  LiveState state;
  loadRunFolder(run, state);
  const nlohmann::json s = state.stateJson();
  EXPECT_EQ(s["trajectory"].size(), 2u);
  EXPECT_EQ(s["keyframes"].size(), 1u);
  EXPECT_EQ(s["points"].size(), 2u);
  EXPECT_EQ(s["summary"]["frames"], 2);
  EXPECT_EQ(s["info"]["live"], false);
  EXPECT_EQ(s["files"], nlohmann::json::array({"overlays/1.000000.png"}));
}

TEST(LoadRunFolder, ShowsTheDenseProductsAndTheGroundTruthOfReportHtml) {
  const fs::path run = amos::testing::scratchDirForThisTest("viewer_run_folder_") / "run";
  test::writeRunFolder(run, true);
  LiveState state;
  loadRunFolder(run, state);
  const nlohmann::json s = state.stateJson();
  EXPECT_EQ(s["points"].size(), 404u);
  EXPECT_EQ(s["trajectory"].size(), 60u);
  ASSERT_EQ(s["ground_truth"].size(), 60u);
  EXPECT_NEAR(s["ground_truth"][0][1].get<double>(), 1.05, 1e-6);
  EXPECT_EQ(s["info"]["has_ground_truth"], true);
  EXPECT_EQ(s["summary"]["stages"]["frame.track"]["median_ms"], 12.5);
  ASSERT_TRUE(s["dense"].contains("mesh")) << s["dense"].dump();
  EXPECT_EQ(s["dense"]["mesh"]["vertices"], 8);
  EXPECT_EQ(s["dense"]["mesh"]["triangles"], 4);
  EXPECT_EQ(s["dense"]["cloud"]["vertices"], 900);
  EXPECT_EQ(s["dense"]["removed"]["vertices"], 400);
  EXPECT_EQ(s["dense"]["removed"]["triangles"], 0);
  ASSERT_NE(state.denseLayer("mesh"), nullptr);
  EXPECT_EQ(state.denseLayer("mesh")->size(), 8u + 8 * 15 + 4 * 12);
}

TEST(LoadRunFolder, WithoutDenseProductsOrReportThoseLayersAreEmpty) {
  const fs::path run = amos::testing::scratchDirForThisTest("viewer_run_folder_") / "run";
  test::writeRunFolder(run, false);
  fs::remove(run / "report.html");
  LiveState state;
  loadRunFolder(run, state);
  const nlohmann::json s = state.stateJson();
  EXPECT_TRUE(s["dense"].empty());
  EXPECT_TRUE(s["ground_truth"].empty());
  EXPECT_EQ(s["info"]["has_ground_truth"], false);
  EXPECT_EQ(s["trajectory"].size(), 60u);
}

TEST(LoadRunFolder, ADenseProductThatCannotBeReadIsLeftOut) {
  const fs::path run = amos::testing::scratchDirForThisTest("viewer_run_folder_") / "run";
  test::writeRunFolder(run, true);
  write(run / "mesh.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n");
  LiveState state;
  loadRunFolder(run, state);
  const nlohmann::json s = state.stateJson();
  EXPECT_FALSE(s["dense"].contains("mesh"));
  EXPECT_TRUE(s["dense"].contains("cloud"));
}

TEST(LoadRunFolder, TheMaskOverlaysOfReportHtmlAreShownWithoutOverlayFiles) {
  const fs::path run = amos::testing::scratchDirForThisTest("viewer_run_folder_") / "run";
  test::writeRunFolder(run, false);
  write(run / "report.html", reportHtml({{"overlays", {{{"index", 7}, {"t", 1.5}, {"jpeg", "QUJD"}}}}}));
  LiveState state;
  loadRunFolder(run, state);
  const nlohmann::json files = state.stateJson()["files"];
  ASSERT_EQ(files.size(), 1u) << files.dump();
  EXPECT_EQ(files[0]["src"], "data:image/jpeg;base64,QUJD");
  EXPECT_EQ(files[0]["title"], "frame 7");
}

TEST(LoadRunFolder, AFolderWithoutARunIsAnError) {
  const fs::path empty = amos::testing::scratchDirForThisTest("viewer_run_folder_");
  LiveState state;
  EXPECT_THROW(loadRunFolder(empty, state), core::Error);
}

}  // namespace
}  // namespace amos::viewer
