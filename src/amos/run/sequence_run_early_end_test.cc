// A run that ends before its sequence does, stopped from outside (a signal: SequenceRunOptions::stop) or by a
// worker thread's failure: the frames processed so far are finished, evaluated and can be written, and the run
// says how it ended.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "amos/config/settings.h"
#include "amos/core/error.h"
#include "amos/report/run_report.h"
#include "amos/run/sequence_run.h"
#include "amos/synth/sequence.h"
#include "amos/testing/scratch_dir.h"
#include "amos/testing/test_inputs.h"

namespace amos::run {
namespace {

namespace fs = std::filesystem;

using amos::testing::kTum3;
constexpr std::size_t kEarlyEndFrames = 30;

SequenceRunOptions optionsFor(const std::string& mode) {
  SequenceRunOptions options;
  options.sequence_dir = synth::cachedSequence(
      (fs::path(AMOS_BINARY_DIR) / "test_outputs" / "synth_cache").string(), "static_xyz", 1, kEarlyEndFrames);
  options.mode = mode;
  options.deterministic = true;
  return options;
}

nlohmann::json writtenStats(const SequenceRunResult& r, const std::string& name) {
  const fs::path out = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "early_end" / name;
  fs::remove_all(out);
  report::writeRunOutputs(out.string(), r.slam(), r.info);
  EXPECT_TRUE(fs::exists(out / "trajectory.txt"));
  EXPECT_TRUE(fs::exists(out / "keyframes.txt"));
  EXPECT_TRUE(fs::exists(out / "map.ply"));
  std::ifstream in(out / "stats.json");
  return nlohmann::json::parse(in);
}

// The stop flag (what SIGINT / SIGTERM set) is read at frame boundaries: set after the 5th frame, the run ends
// with exactly 5 frames, in every mode.
TEST(SequenceRunEarlyEnd, StopEndsTheRunAtTheNextFrameBoundary) {
  for (const std::string mode : {"none", "geometry"}) {
    core::StopRequest stop;
    SequenceRunOptions options = optionsFor(mode);
    options.stop = &stop;
    options.on_frame = [&stop](const SequenceProgress& p) {
      if (p.processed == 5) stop.request();
    };
    const SequenceRunResult r = runSequence(config::loadSettings(kTum3), options);
    EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kInterrupted) << mode;
    EXPECT_FALSE(r.failure) << mode;
    EXPECT_EQ(r.slam().stats().frames, 5u) << mode;
    EXPECT_EQ(r.trajectory.size(), 5u) << mode;
    ASSERT_TRUE(r.info.evaluation) << mode;
    EXPECT_EQ(r.info.evaluation->ate_pairs, 5u) << mode;
    const nlohmann::json stats = writtenStats(r, "stop_" + mode);
    EXPECT_EQ(stats["end"]["status"], "interrupted") << mode;
    EXPECT_EQ(stats["frames"], 5) << mode;
  }
}

// A stop requested before the first frame ends the run with none: outputs are still written (empty).
TEST(SequenceRunEarlyEnd, StopBeforeTheFirstFrame) {
  core::StopRequest stop;
  stop.request();
  SequenceRunOptions options = optionsFor("none");
  options.stop = &stop;
  const SequenceRunResult r = runSequence(config::loadSettings(kTum3), options);
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kInterrupted);
  EXPECT_EQ(r.slam().stats().frames, 0u);
  EXPECT_TRUE(r.trajectory.empty());
  EXPECT_EQ(writtenStats(r, "stop_first")["end"]["status"], "interrupted");
}

// A copy of the test sequence whose 6th frame comes ten minutes after the 5th (its first 8 frames).
fs::path sequenceWithALongGap() {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_gap_") / "sequence";
  fs::copy(optionsFor("none").sequence_dir, dir, fs::copy_options::recursive);
  std::ifstream in(dir / "associations.txt");
  std::stringstream rows;
  rows << in.rdbuf();
  in.close();
  std::ofstream out(dir / "associations.txt");
  int k = 0;
  for (std::string row; std::getline(rows, row) && k < 8;) {
    if (row.empty() || row[0] == '#') continue;
    std::istringstream fields(row);
    double t_rgb = 0, t_depth = 0;
    std::string rgb, depth;
    fields >> t_rgb >> rgb >> t_depth >> depth;
    const double late = k >= 5 ? 600.0 : 0.0;
    out << std::fixed << t_rgb + late << " " << rgb << " " << t_depth + late << " " << depth << "\n";
    ++k;
  }
  return dir;
}

// A stop requested while a --realtime replay waits for a frame due ten minutes later ends the run at once: the
// wait is woken, not sat out (before, Ctrl-C waited 11.5 minutes on a Bonn sequence's gap).
TEST(SequenceRunEarlyEnd, StopEndsAPacedRunWaitingForALateFrameAtOnce) {
  SequenceRunOptions options = optionsFor("none");
  options.sequence_dir = sequenceWithALongGap().string();
  options.source = FrameSourceKind::kRealtime;
  core::StopRequest stop;
  options.stop = &stop;
  std::thread requester;
  options.on_frame = [&](const SequenceProgress& p) {
    // The 5th frame is never dropped: it is the newest one for ten minutes.
    if (p.frame == 5 && !requester.joinable()) {
      requester = std::thread([&stop] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the loop is waiting for the 6th by then
        stop.request();
      });
    }
  };
  const auto start = std::chrono::steady_clock::now();
  const SequenceRunResult r = runSequence(config::loadSettings(kTum3), options);
  const auto took = std::chrono::steady_clock::now() - start;
  ASSERT_TRUE(requester.joinable());
  requester.join();
  EXPECT_LT(took, std::chrono::seconds(30));
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kInterrupted);
  EXPECT_FALSE(r.failure);
  EXPECT_LE(r.slam().stats().frames, 5u);
  EXPECT_EQ(r.info.source->delivered, 5u);
}

// A failure of the mapping thread (injected at the third keyframe, after loop closing's hook) ends the run at the
// frame that made that keyframe: the frames before it are kept and evaluated, the error is returned, not logged
// and forgotten.
TEST(SequenceRunEarlyEnd, MappingFailureEndsTheRunWithOutputsKept) {
  SequenceRunOptions options = optionsFor("none");
  options.after_keyframe = [](const map::KeyFramePtr& kf) {
    if (kf->id() == 2) throw std::runtime_error("injected failure");
  };
  const SequenceRunResult r = runSequence(config::loadSettings(kTum3), options);
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kFailed);
  EXPECT_NE(r.info.end.reason.find("local mapping failed on keyframe 2: injected failure"), std::string::npos)
      << r.info.end.reason;
  ASSERT_TRUE(r.failure);
  EXPECT_THROW(r.rethrowFailure(), core::Error);
  const std::size_t frames = r.slam().stats().frames;
  EXPECT_GE(frames, 2u);
  EXPECT_LT(frames, kEarlyEndFrames);
  EXPECT_EQ(r.trajectory.size(), frames);
  ASSERT_TRUE(r.info.evaluation);
  EXPECT_LT(r.info.evaluation->ate_rmse_m, 0.01);
  const nlohmann::json stats = writtenStats(r, "mapping_failure");
  EXPECT_EQ(stats["end"]["status"], "failed");
  EXPECT_EQ(stats["frames"], frames);
}

// Without lock-step the failure reaches the run at a later frame boundary, or at the latest when the mapping
// drains its queue at the end: either way the run reports it.
TEST(SequenceRunEarlyEnd, ThreadedMappingFailureIsReported) {
  SequenceRunOptions options = optionsFor("none");
  options.deterministic = false;
  options.after_keyframe = [](const map::KeyFramePtr& kf) {
    if (kf->id() == 1) throw std::runtime_error("injected failure");
  };
  const SequenceRunResult r = runSequence(config::loadSettings(kTum3), options);
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kFailed);
  EXPECT_NE(r.info.end.reason.find("injected failure"), std::string::npos) << r.info.end.reason;
  EXPECT_EQ(r.trajectory.size(), r.slam().stats().frames);
}

TEST(SequenceRunEarlyEnd, ACompleteRunSaysSo) {
  const SequenceRunResult r = runSequence(config::loadSettings(kTum3), optionsFor("none"));
  EXPECT_EQ(r.info.end.status, report::RunEnd::Status::kComplete);
  EXPECT_TRUE(r.info.end.reason.empty());
  EXPECT_FALSE(r.failure);
  EXPECT_NO_THROW(r.rethrowFailure());
  EXPECT_EQ(r.slam().stats().frames, kEarlyEndFrames);
}

}  // namespace
}  // namespace amos::run
