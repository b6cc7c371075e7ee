// runSequence on a synthetic sequence damaged the ways real recordings are: unreadable, wrongly sized and 8-bit
// frames, a file gone mid-run, and depth dropouts (all-zero and nearly empty depth images). The run never aborts:
// bad frames are skipped and counted, dropout frames are tracked from their colour images against the map.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "amos/config/settings.h"
#include "amos/core/error.h"
#include "amos/io/dataset.h"
#include "amos/report/run_report.h"
#include "amos/run/sequence_run.h"
#include "amos/synth/sequence.h"
#include "amos/testing/test_inputs.h"

namespace amos::run {
namespace {

namespace fs = std::filesystem;

using amos::testing::kTum3;
constexpr int kFrames = 30;

// A fresh copy of the 30-frame static_xyz sequence (rendered once per build tree) in test_outputs/<name>.
fs::path freshSequence(const std::string& name) {
  const fs::path root = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "damaged_input";
  const std::string cached =
      synth::cachedSequence((fs::path(AMOS_BINARY_DIR) / "test_outputs" / "synth_cache").string(), "static_xyz", 1,
                            kFrames);
  const fs::path dir = root / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  fs::copy(cached, dir, fs::copy_options::recursive);
  return dir;
}

std::vector<io::AssociatedFrame> framesOf(const fs::path& dir) { return io::indexSequence(dir.string()).frames; }

// Clears a depth image but for its first `keep_valid` pixels (row by row).
void zeroDepth(const std::string& depth_file, int keep_valid) {
  cv::Mat d = cv::imread(depth_file, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(d.type(), CV_16U);
  for (int k = keep_valid; k < static_cast<int>(d.total()); ++k) d.at<std::uint16_t>(k / d.cols, k % d.cols) = 0;
  cv::imwrite(depth_file, d);
}

SequenceRunResult runOn(const fs::path& dir, const std::string& mode, bool strict = false) {
  SequenceRunOptions options;
  options.sequence_dir = dir.string();
  options.mode = mode;
  options.deterministic = true;
  options.strict = strict;
  return runSequence(config::loadSettings(kTum3), options);
}

// Frames 8-11 of 30 are damaged one way each: a truncated colour PNG, a colour image of the wrong size, an 8-bit
// depth image, a depth file that is missing.
void damage(const fs::path& dir) {
  const auto frames = framesOf(dir);
  fs::resize_file(frames[8].rgb_file, fs::file_size(frames[8].rgb_file) / 3);  // truncated PNG
  cv::Mat small;
  cv::resize(cv::imread(frames[9].rgb_file), small, {320, 240});
  cv::imwrite(frames[9].rgb_file, small);                                             // wrong size
  cv::imwrite(frames[10].depth_file, cv::Mat(480, 640, CV_8U, cv::Scalar(100)));     // 8-bit depth
  fs::remove(frames[11].depth_file);                                                 // missing
}

TEST(SequenceRunDamagedInput, BadFramesAreSkippedAndCountedByReason) {
  const fs::path dir = freshSequence("bad_frames");
  damage(dir);
  const SequenceRunResult r = runOn(dir, "none");
  const io::SkippedFrames& skipped = r.info.skipped_frames;
  EXPECT_EQ(skipped.count(io::FrameProblem::kUnreadable), 1u);
  EXPECT_EQ(skipped.count(io::FrameProblem::kWrongSize), 1u);
  EXPECT_EQ(skipped.count(io::FrameProblem::kWrongFormat), 1u);
  EXPECT_EQ(skipped.count(io::FrameProblem::kMissing), 1u);
  const system::SlamStats s = r.slam().stats();
  EXPECT_EQ(s.frames, kFrames - 4u);
  EXPECT_EQ(s.tracked, kFrames - 4u);
  EXPECT_EQ(r.trajectory.size(), kFrames - 4u);
  ASSERT_TRUE(r.info.evaluation);
  EXPECT_LT(r.info.evaluation->ate_rmse_m, 0.01);

  const fs::path out = dir / "run";
  report::writeRunOutputs(out.string(), r.slam(), r.info);
  std::ifstream in(out / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["skipped_frames"], nlohmann::json({{"missing", 1}, {"unreadable", 1}, {"wrong_size", 1},
                                                     {"wrong_format", 1}, {"blank", 0}}));
  EXPECT_EQ(stats["depth_dropouts"]["frames"], 0);
}

// --strict: the first bad frame ends the run with its error; the frames before it are kept.
TEST(SequenceRunDamagedInput, StrictMakesABadFrameAnError) {
  const fs::path dir = freshSequence("strict");
  const auto frames = framesOf(dir);
  fs::resize_file(frames[8].rgb_file, fs::file_size(frames[8].rgb_file) / 3);
  const SequenceRunResult r = runOn(dir, "none", /*strict=*/true);
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kFailed);
  EXPECT_EQ(r.slam().stats().frames, 8u);
  EXPECT_EQ(r.trajectory.size(), 8u);
  try {
    r.rethrowFailure();
    FAIL() << "expected a core::Error";
  } catch (const io::FrameLoadError& e) {
    EXPECT_EQ(e.problem(), io::FrameProblem::kUnreadable);
    EXPECT_EQ(e.file(), frames[8].rgb_file);
  }
}

// Depth dropouts once the map exists (all-zero depth in frames 12-15, 0.3 % valid pixels in frame 20): each
// frame is tracked from its colour image against the map, in plain SLAM and with the geometric front end.
TEST(SequenceRunDamagedInput, DepthDropoutsAreTrackedFromColour) {
  const fs::path dir = freshSequence("dropouts");
  const auto frames = framesOf(dir);
  for (int k = 12; k < 16; ++k) zeroDepth(frames[k].depth_file, 0);
  zeroDepth(frames[20].depth_file, 640 * 480 * 3 / 1000);
  for (const std::string mode : {"none", "geometry"}) {
    const SequenceRunResult r = runOn(dir, mode);
    EXPECT_EQ(r.info.depth_dropouts.frames, 5u) << mode;
    EXPECT_EQ(r.info.depth_dropouts.tracked, 5u) << mode;
    EXPECT_EQ(r.info.depth_dropouts.lost, 0u) << mode;
    EXPECT_EQ(r.info.skipped_frames.total(), 0u) << mode;
    const system::SlamStats s = r.slam().stats();
    EXPECT_EQ(s.frames, static_cast<std::size_t>(kFrames)) << mode;
    EXPECT_EQ(s.tracked, static_cast<std::size_t>(kFrames)) << mode;
    ASSERT_TRUE(r.info.evaluation) << mode;
    EXPECT_EQ(r.info.evaluation->ate_pairs, static_cast<std::size_t>(kFrames)) << mode;
    EXPECT_LT(r.info.evaluation->ate_rmse_m, 0.01) << mode;
  }
}

// A dropout before the map exists: nothing to track against, so those frames wait (not initialised) and the map
// starts at the first frame with depth.
TEST(SequenceRunDamagedInput, DropoutsBeforeTheMapDelayItsStart) {
  const fs::path dir = freshSequence("dropouts_first");
  const auto frames = framesOf(dir);
  for (int k = 0; k < 3; ++k) zeroDepth(frames[k].depth_file, 0);
  const SequenceRunResult r = runOn(dir, "none");
  EXPECT_EQ(r.info.depth_dropouts.frames, 3u);
  EXPECT_EQ(r.info.depth_dropouts.tracked, 0u);
  EXPECT_EQ(r.info.depth_dropouts.lost, 0u);
  const system::SlamStats s = r.slam().stats();
  EXPECT_EQ(s.not_initialized, 3u);
  EXPECT_EQ(s.tracked, kFrames - 3u);
  EXPECT_EQ(r.trajectory.size(), kFrames - 3u);
}

// Settings that cannot fit the input are an error before the run: a sequence whose frames are 320x240 with a
// config that says 640x480 (before, every frame was skipped as wrong_size and the run "succeeded" empty).
TEST(SequenceRunDamagedInput, ACameraSizeThatDoesNotFitTheFramesIsAnErrorBeforeTheRun) {
  const fs::path dir = freshSequence("wrong_camera_size");
  const auto frames = framesOf(dir);
  cv::Mat small;
  cv::resize(cv::imread(frames[0].rgb_file), small, {320, 240});
  cv::imwrite(frames[0].rgb_file, small);
  SequenceRunOptions options;
  options.sequence_dir = dir.string();
  options.config_label = kTum3;
  try {
    runSequence(config::loadSettings(kTum3), options);
    FAIL() << "expected a core::Error";
  } catch (const core::Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("Camera.width x Camera.height is 640x480 in " + kTum3), std::string::npos) << message;
    EXPECT_NE(message.find("are 320x240 ('" + frames[0].rgb_file + "')"), std::string::npos) << message;
  }
}

// A run in which every frame was skipped is a failure with a message, not a success with an empty trajectory.
TEST(SequenceRunDamagedInput, ARunWithEveryFrameSkippedIsAFailure) {
  const fs::path dir = freshSequence("all_skipped");
  for (const io::AssociatedFrame& f : framesOf(dir)) fs::resize_file(f.rgb_file, fs::file_size(f.rgb_file) / 3);
  const SequenceRunResult r = runOn(dir, "none");
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kFailed);
  ASSERT_TRUE(r.failure);
  EXPECT_NE(r.info.end.reason.find("every frame of " + dir.string() + " was skipped (unreadable 30)"),
            std::string::npos)
      << r.info.end.reason;
  EXPECT_THROW(r.rethrowFailure(), core::Error);
  EXPECT_EQ(r.slam().stats().frames, 0u);
}

// An observer whose measurement fails after the run (what a failing evaluation does) costs nothing: the run
// returns, complete, and its outputs can be written.
TEST(SequenceRunDamagedInput, AFailureAfterTheRunLeavesTheOutputs) {
  struct FailingMeasure : RunObserver {
    void onFrame(const FrameSnapshot&) override {}
    void addToInfo(const std::vector<io::StampedPose>&, report::RunInfo&) override {
      throw core::Error("evaluation failed");
    }
  } failing;
  SequenceRunOptions options;
  options.sequence_dir = freshSequence("failing_measure").string();
  options.mode = "none";
  options.deterministic = true;
  options.observers = {&failing};
  const SequenceRunResult r = runSequence(config::loadSettings(kTum3), options);
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kComplete);
  EXPECT_FALSE(r.failure);
  EXPECT_EQ(r.trajectory.size(), static_cast<std::size_t>(kFrames));
  EXPECT_TRUE(r.info.evaluation);  // the run's own evaluation came first
}

}  // namespace
}  // namespace amos::run
