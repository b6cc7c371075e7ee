// Maps that last, end to end on a synthetic sequence with ground truth: a run saves its map (--save-map), a second
// run loads it and localises the rest of the sequence from a cold start without adding to the map (--localize),
// and a third extends it (--load-map alone) and saves it again.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "amos/config/settings.h"
#include "amos/core/error.h"
#include "amos/run/sequence_run.h"
#include "amos/synth/sequence.h"
#include "amos/testing/test_inputs.h"

namespace amos::run {
namespace {

namespace fs = std::filesystem;

using amos::testing::kTum3;

std::string sequence() {
  return synth::cachedSequence((fs::path(AMOS_BINARY_DIR) / "test_outputs" / "synth_cache").string(), "static_xyz",
                               1, 60);
}

SequenceRunOptions baseOptions() {
  SequenceRunOptions options;
  options.sequence_dir = sequence();
  options.mode = "none";
  options.deterministic = true;
  return options;
}

TEST(MapSession, SaveThenLocalizeTheRestFromAColdStartThenExtend) {
  const fs::path dir = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "map_session";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const config::Settings settings = config::loadSettings(kTum3);
  const std::string first_map = (dir / "first.map").string();

  SequenceRunOptions mapping = baseOptions();
  mapping.max_frames = 30;
  const SequenceRunResult first = runSequence(settings, mapping);
  ASSERT_FALSE(first.failure);
  const mapio::MapFileSummary saved = first.slam().saveMap(first_map);
  ASSERT_GE(saved.keyframes, 2u);

  // Frames 20-59: the last third of the mapped part, then 30 frames the map never saw from there.
  SequenceRunOptions localize = baseOptions();
  localize.first_frame = 20;
  localize.load_map = first_map;
  localize.localize = true;
  const SequenceRunResult second = runSequence(settings, localize);
  ASSERT_FALSE(second.failure);
  const system::SlamStats s = second.slam().stats();
  EXPECT_EQ(s.frames, 40u);
  EXPECT_GE(s.tracked, 38u);  // the first frame is relocalised at once (or the second)
  EXPECT_GE(s.relocalized, 1u);
  EXPECT_EQ(s.keyframes_created, 0u);
  EXPECT_EQ(s.keyframes, saved.keyframes);
  EXPECT_EQ(s.map_points, saved.map_points);
  EXPECT_EQ(second.trajectory.size(), s.tracked);  // only the localised frames
  ASSERT_TRUE(second.info.evaluation);
  EXPECT_LT(second.info.evaluation->ate_rmse_m, 0.01);

  // Without --localize the loaded map grows, and the grown map saves and loads again.
  SequenceRunOptions extend = baseOptions();
  extend.first_frame = 25;
  extend.load_map = first_map;
  const SequenceRunResult third = runSequence(settings, extend);
  ASSERT_FALSE(third.failure);
  EXPECT_GT(third.slam().stats().keyframes_created, 0u);
  EXPECT_GT(third.slam().stats().keyframes, saved.keyframes);
  const std::string second_map = (dir / "second.map").string();
  const mapio::MapFileSummary resaved = third.slam().saveMap(second_map);
  map::Map reloaded;
  EXPECT_EQ(mapio::loadMap(second_map, third.slam().sensor(), reloaded).keyframes, resaved.keyframes);
}

TEST(MapSession, LocalizeNeedsAMapAndABadMapIsAnErrorBeforeTheFirstFrame) {
  const config::Settings settings = config::loadSettings(kTum3);
  SequenceRunOptions options = baseOptions();
  options.max_frames = 5;
  options.localize = true;
  EXPECT_THROW(runSequence(settings, options), core::Error);
  const fs::path bad = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "map_session_bad.map";
  fs::create_directories(bad.parent_path());
  { std::ofstream(bad) << "not a map"; }
  options.load_map = bad.string();
  try {
    runSequence(settings, options);
    FAIL() << "no error";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string() + ": not a map file or truncated"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace amos::run
