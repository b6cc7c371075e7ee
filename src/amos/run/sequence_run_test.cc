#include "amos/run/sequence_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "amos/config/settings.h"
#include "amos/synth/sequence.h"
#include "amos/testing/shared_data.h"
#include "amos/testing/test_inputs.h"

namespace amos::run {
namespace {

using amos::testing::kFr2Data;
using amos::testing::kFr2;
using amos::testing::kTum2;
using amos::testing::kTum3;

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

SequenceRunResult runFr2(bool deterministic) {
  SequenceRunOptions options;
  options.sequence_dir = kFr2;
  options.deterministic = deterministic;
  return runSequence(config::loadSettings(kTum2), options);
}

// End to end on real data. ORB-SLAM2 scores 3.76 mm ATE on these 50 frames; this system scores 4.94 mm in
// deterministic mode today (4.45 mm with ORB-SLAM2's keyframe ratio of 0.75 instead of 0.85, which makes 6
// keyframes here instead of 10 but leaves room laps drifting further: see TrackerOptions::keyframe_ref_ratio;
// tracking alone, without local BA, 3.7 mm). The bound guards against regressions while the 3.8 mm target is
// still open.
TEST(SequenceRun, TumFr2DeskFirst50TracksEveryFrameAccurately) {
  AMOS_REQUIRE_DATA(kFr2Data);
  const SequenceRunResult r = runFr2(true);
  ASSERT_TRUE(r.engine);
  const system::SlamStats s = r.slam().stats();
  EXPECT_EQ(s.frames, 50u);
  EXPECT_EQ(s.tracked, 50u);
  EXPECT_EQ(s.lost, 0u);
  EXPECT_EQ(r.trajectory.size(), 50u);
  ASSERT_TRUE(r.info.evaluation.has_value());
  EXPECT_EQ(r.info.evaluation->ate_pairs, 50u);
  EXPECT_LE(r.info.evaluation->ate_rmse_m, 0.0053);
  std::cout << "ATE RMSE " << r.info.evaluation->ate_rmse_m << " m, keyframes " << s.keyframes << ", points "
            << s.map_points << "\n";
}

// --deterministic: the same input gives the same trajectory file, byte for byte.
TEST(SequenceRun, DeterministicModeIsBitIdentical) {
  AMOS_REQUIRE_DATA(kFr2Data);
  const std::filesystem::path dir = std::filesystem::path(AMOS_BINARY_DIR) / "test_outputs" / "determinism";
  std::string bytes[2];
  for (int run = 0; run < 2; ++run) {
    const SequenceRunResult r = runFr2(true);
    const std::string out = (dir / std::to_string(run)).string();
    report::writeRunOutputs(out, r.slam(), r.info);
    bytes[run] = readFile(out + "/trajectory.txt");
    EXPECT_TRUE(std::filesystem::exists(out + "/keyframes.txt"));
    EXPECT_TRUE(std::filesystem::exists(out + "/map.ply"));
    EXPECT_TRUE(std::filesystem::exists(out + "/stats.json"));
  }
  EXPECT_GT(bytes[0].size(), 1000u);
  EXPECT_EQ(bytes[0], bytes[1]);
}

// --save-masks on a short synthetic sequence with ground-truth movers (two people walking in view from the first
// frame): one 8-bit mask per frame named by the RGB time stamp, the overlays, and the mask scored against the
// movers in stats.json.
TEST(SequenceRun, SavesMasksAndScoresThemAgainstSyntheticGroundTruth) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "save_masks";
  fs::remove_all(root);
  synth::SequenceOptions synth_options;
  synth_options.preset = "walking_static";
  synth_options.seed = 1;
  synth_options.frames = 12;
  synth::renderSequence(synth_options, (root / "sequence").string());

  SequenceRunOptions options;
  options.sequence_dir = (root / "sequence").string();
  options.mode = "geometry";
  options.deterministic = true;
  options.masks_output_dir = (root / "run").string();
  options.overlay_count = 4;
  const SequenceRunResult r = runSequence(config::loadSettings(kTum3), options);
  report::writeRunOutputs((root / "run").string(), r.slam(), r.info);

  std::size_t masks = 0, overlays = 0;
  for (const auto& e : fs::directory_iterator(root / "sequence" / "rgb")) {
    const fs::path mask = root / "run" / "masks" / e.path().filename();
    ASSERT_TRUE(fs::exists(mask)) << mask;
    const cv::Mat m = cv::imread(mask.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(m.type(), CV_8UC1);
    ASSERT_EQ(m.size(), cv::Size(640, 480));
    EXPECT_EQ(cv::countNonZero((m != 0) & (m != 255)), 0);
    ++masks;
  }
  EXPECT_EQ(masks, 12u);
  for (const auto& e : fs::directory_iterator(root / "run" / "overlays")) {
    EXPECT_TRUE(fs::exists(root / "sequence" / "rgb" / e.path().filename())) << e.path();
    ++overlays;
  }
  EXPECT_EQ(overlays, 4u);

  ASSERT_TRUE(r.info.mask_accuracy.has_value());
  EXPECT_EQ(r.info.mask_accuracy->frames, 12);
  EXPECT_EQ(r.info.mask_accuracy->frames_with_truth, 12);
  std::ifstream in(root / "run" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  ASSERT_TRUE(stats.contains("mask_accuracy"));
  EXPECT_EQ(stats["mask_accuracy"]["frames"], 12);
  EXPECT_TRUE(stats["mask_accuracy"].contains("recall"));
}

}  // namespace
}  // namespace amos::run
