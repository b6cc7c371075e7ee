// amos::Slam's dense map (Options::dense, include/amos/dense_map.h) on a short synthetic sequence (mode geometry,
// deterministic): the same mesh file, byte for byte, as `amos-slam run --dense`'s observer makes of the same
// frames; the Dense.* settings reach it; its errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "amos/config/settings.h"
#include "amos/dense_map.h"
#include "amos/run/sequence_run.h"
#include "amos/run/settings_sections.h"
#include "amos/sequence_folder.h"
#include "amos/slam.h"
#include "amos/synth/sequence.h"
#include "amos/testing/error_of.h"
#include "amos/testing/file_text.h"
#include "amos/testing/scratch_dir.h"
#include "amos/testing/test_inputs.h"

#ifdef AMOS_HAVE_OPEN3D
#include "amos/run/dense_observer.h"
#endif

namespace amos {
namespace {

namespace fs = std::filesystem;

using amos::testing::kTum3;

std::string sequence() {
  return synth::cachedSequence((fs::path(AMOS_BINARY_DIR) / "test_outputs" / "api_sequences").string(), "walking_xyz",
                               1, 30);
}


Options denseOptions() {
  Options o;
  o.settings_file = kTum3;
  o.mode = Mode::kGeometry;
  o.deterministic = true;
  o.dense = true;
  return o;
}

void trackAll(Slam& slam, const std::string& dir) {
  const SequenceFolder folder(dir);
  for (std::size_t i = 0; i < folder.size(); ++i) {
    const RgbdImages f = folder.read(i);
    slam.track(f.bgr, f.depth, f.timestamp);
  }
}

// Whether two files hold the same bytes (the message gives their sizes, not their binary contents).
::testing::AssertionResult sameBytes(const fs::path& a, const fs::path& b) {
  const std::string x = testing::fileText(a), y = testing::fileText(b);
  if (!x.empty() && x == y) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " (" << x.size() << " bytes) and " << b << " (" << y.size()
                                       << " bytes) differ";
}

using amos::testing::errorOf;

#ifdef AMOS_HAVE_OPEN3D

// The same frames, masks, poses and settings as the run's observer: the same final map, so the same mesh.ply.
TEST(SlamDense, MeshIsTheRunsByteForByte) {
  const std::string seq = sequence();
  const fs::path dir = testing::scratchDirForThisTest("amos_api_dense_");
  const config::Settings settings = run::loadSettings(kTum3);
  run::DenseObserver observer(settings.section<dense::DenseOptions>(), dir.string());
  run::SequenceRunOptions run_options;
  run_options.sequence_dir = seq;
  run_options.mode = "geometry";
  run_options.deterministic = true;
  run_options.observers = {&observer};
  run::SequenceRunResult run = run::runSequence(settings, run_options);
  observer.finishMap(run.trajectory, run.info);

  Slam slam(denseOptions());
  trackAll(slam, seq);
  EXPECT_THROW(slam.denseMap(), std::runtime_error);  // before finish()
  slam.finish();
  const DenseMap map = slam.denseMap();
  EXPECT_GT(map.mesh.vertices.size(), 1000u);
  EXPECT_EQ(map.mesh.colours.size(), map.mesh.vertices.size());
  EXPECT_GT(map.mesh.triangles.size(), 1000u);
  EXPECT_GT(map.cloud.points.size(), 1000u);
  EXPECT_GT(map.frames_fused, 20u);
  writeMeshPly(map, (dir / "api_mesh.ply").string());
  writeCloudPly(map, (dir / "api_cloud.ply").string());
  EXPECT_TRUE(sameBytes(dir / "api_mesh.ply", dir / "mesh.ply"));
  EXPECT_TRUE(sameBytes(dir / "api_cloud.ply", dir / "cloud.ply"));
  if (map.grid) {
    EXPECT_EQ(map.grid->cells.size(), static_cast<std::size_t>(map.grid->rows) * map.grid->cols);
    writeFloorPlan(map, (dir / "api_occupancy").string());
    EXPECT_TRUE(sameBytes(dir / "api_occupancy.pgm", dir / "occupancy.pgm"));
  } else {
    EXPECT_NE(errorOf([&] { writeFloorPlan(map, (dir / "none").string()); }).find("no floor plan"),
              std::string::npos);
  }
}

// The settings' Dense.* keys are read (an override of one is accepted and used) and checked.
TEST(SlamDense, DenseSettingsAndOverridesApply) {
  Options coarse = denseOptions();
  coarse.overrides = {{"Dense.voxelSize", "0.08"}, {"Dense.truncation", "0.24"}, {"Dense.liveEvery", "1"}};
  Slam slam(coarse);
  trackAll(slam, sequence());
  const std::optional<DenseSnapshot> live = slam.denseSnapshot();
  slam.finish();
  const std::size_t coarse_vertices = slam.denseMap().mesh.vertices.size();
  Slam fine(denseOptions());
  trackAll(fine, sequence());
  fine.finish();
  EXPECT_LT(coarse_vertices, fine.denseMap().mesh.vertices.size() / 2);
  if (live) {
    EXPECT_EQ(live->cloud.colours.size(), live->cloud.points.size());
  }

  Options bad = denseOptions();
  bad.overrides = {{"Dense.voxelSize", "-1"}};
  EXPECT_NE(errorOf([&] { Slam s(bad); }).find("voxel"), std::string::npos);
}

// The floor plan of the live surface (what amos_slam_node publishes while it runs): once the live volume holds
// every frame, the same floor as the final map's, and a grid with free and occupied cells.
TEST(SlamDense, LiveGridFindsTheFinalMapsFloor) {
  Options o = denseOptions();
  o.overrides = {{"Dense.liveEvery", "1"}, {"Dense.livePeriod", "0.001"}};  // a new live surface every frame
  Slam slam(o);
  EXPECT_FALSE(slam.denseLiveGrid());  // no live surface yet
  trackAll(slam, sequence());
  slam.finish();  // the fusion queue drained: the live surface holds every frame
  const std::optional<OccupancyGrid> live = slam.denseLiveGrid();
  const DenseMap map = slam.denseMap();
  ASSERT_TRUE(map.grid);
  ASSERT_TRUE(live);
  EXPECT_EQ(live->cells.size(), static_cast<std::size_t>(live->rows) * live->cols);
  EXPECT_GT(std::count(live->cells.begin(), live->cells.end(), OccupancyGrid::kFree), 0);
  EXPECT_GT(std::count(live->cells.begin(), live->cells.end(), OccupancyGrid::kOccupied), 0);
  EXPECT_GT(live->floor_normal.dot(map.grid->floor_normal), std::cos(5 * M_PI / 180));
  EXPECT_NEAR(live->floor_offset, map.grid->floor_offset, 0.05);
}

#else

TEST(SlamDense, DenseWithoutOpen3DIsAnErrorSayingSo) {
  EXPECT_FALSE(denseMappingAvailable());
  EXPECT_NE(errorOf([] { Slam s(denseOptions()); }).find("Open3D"), std::string::npos);
}

#endif

TEST(SlamDense, DenseCallsWithoutDenseAreErrors) {
  Options o = denseOptions();
  o.dense = false;
  Slam slam(o);
  slam.finish();
  EXPECT_NE(errorOf([&] { slam.denseMap(); }).find("Options::dense"), std::string::npos);
  EXPECT_NE(errorOf([&] { slam.denseSnapshot(); }).find("Options::dense"), std::string::npos);
  EXPECT_NE(errorOf([&] { slam.denseLiveGrid(); }).find("Options::dense"), std::string::npos);
  EXPECT_NE(errorOf([] { writeFloorPlan(DenseMap{}, "x"); }).find("writeFloorPlan"), std::string::npos);
}

}  // namespace
}  // namespace amos
