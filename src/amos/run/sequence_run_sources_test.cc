// runSequence with each kind of frame source (folder, paced replay, live camera) and with --record.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "amos/config/settings.h"
#include "amos/core/error.h"
#include "amos/io/dataset.h"
#include "amos/report/run_report.h"
#include "amos/run/sequence_run.h"
#include "amos/testing/shared_data.h"
#include "amos/testing/test_inputs.h"

namespace amos::run {
namespace {

namespace fs = std::filesystem;

using amos::testing::kFr2Data;
using amos::testing::kFr2;
using amos::testing::kTum2;

fs::path outputDir(const std::string& name) {
  const fs::path dir = fs::path(AMOS_BINARY_DIR) / "test_outputs" / "sources" / name;
  fs::remove_all(dir);
  return dir;
}

nlohmann::json writeAndReadStats(const SequenceRunResult& r, const fs::path& dir) {
  report::writeRunOutputs(dir.string(), r.slam(), r.info);
  std::ifstream in(dir / "stats.json");
  return nlohmann::json::parse(in);
}

TEST(SequenceRunSources, FolderSourceDeliversAndProcessesEveryFrame) {
  AMOS_REQUIRE_DATA(kFr2Data);
  SequenceRunOptions options;
  options.sequence_dir = kFr2;
  options.max_frames = 20;
  const SequenceRunResult r = runSequence(config::loadSettings(kTum2), options);
  ASSERT_TRUE(r.info.source);
  const report::SourceReport& s = *r.info.source;
  EXPECT_EQ(s.kind, "folder");
  EXPECT_EQ(s.delivered, 20u);
  EXPECT_EQ(s.processed, 20u);
  EXPECT_EQ(s.dropped, 0u);
  ASSERT_EQ(s.latency_ms.size(), 20u);
  for (double ms : s.latency_ms) EXPECT_GT(ms, 0.0);
  EXPECT_EQ(r.trajectory.size(), 20u);
  const nlohmann::json stats = writeAndReadStats(r, outputDir("folder"));
  ASSERT_TRUE(stats.contains("source"));
  EXPECT_EQ(stats["source"]["kind"], "folder");
  EXPECT_EQ(stats["source"]["processed"], 20);
  EXPECT_TRUE(stats["source"]["latency_ms"].contains("median"));
  EXPECT_TRUE(stats["source"]["latency_ms"].contains("p95"));
}

// The 50 fr2 frames replayed at 30 Hz (1.6 s): every frame delivered is either processed or dropped, the
// trajectory holds the processed ones, and it is still evaluated against the ground truth.
TEST(SequenceRunSources, RealtimeReplayProcessesOrDropsEveryFrame) {
  AMOS_REQUIRE_DATA(kFr2Data);
  SequenceRunOptions options;
  options.source = FrameSourceKind::kRealtime;
  options.sequence_dir = kFr2;
  const SequenceRunResult r = runSequence(config::loadSettings(kTum2), options);
  ASSERT_TRUE(r.info.source);
  const report::SourceReport& s = *r.info.source;
  EXPECT_EQ(s.kind, "realtime");
  EXPECT_EQ(s.delivered, 50u);
  EXPECT_EQ(s.processed + s.dropped, s.delivered);
  EXPECT_GE(s.processed, 10u);
  EXPECT_EQ(s.latency_ms.size(), s.processed);
  EXPECT_EQ(r.slam().stats().frames, s.processed);
  EXPECT_EQ(r.trajectory.size(), s.processed);
  EXPECT_GE(r.info.wall_time_s, 1.5);  // paced: 49 frame intervals of fr2's recording
  ASSERT_TRUE(r.info.evaluation);
  EXPECT_LT(r.info.evaluation->ate_rmse_m, 0.05);
  const nlohmann::json stats = writeAndReadStats(r, outputDir("realtime"));
  EXPECT_EQ(stats["source"]["kind"], "realtime");
  EXPECT_EQ(stats["source"]["delivered"], 50);
}

// --record: the recorded folder is a sequence of its own, holding exactly the processed frames, bit for bit.
TEST(SequenceRunSources, RecordingHoldsTheProcessedFramesBitExact) {
  AMOS_REQUIRE_DATA(kFr2Data);
  const config::Settings settings = config::loadSettings(kTum2);
  const fs::path record = outputDir("record");
  SequenceRunOptions options;
  options.sequence_dir = kFr2;
  options.max_frames = 8;
  options.record_dir = record.string();
  const SequenceRunResult r = runSequence(settings, options);
  ASSERT_TRUE(r.info.source);
  EXPECT_EQ(r.info.source->recorded_to, record.string());

  const io::SequenceIndex original = io::indexSequence(kFr2);
  const io::SequenceIndex recorded = io::indexSequence(record.string());
  ASSERT_EQ(recorded.frames.size(), 8u);
  ASSERT_EQ(r.trajectory.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(recorded.frames[i].t_rgb, original.frames[i].t_rgb);
    EXPECT_EQ(recorded.frames[i].t_rgb, r.trajectory[i].timestamp);
    const io::RgbdFrame a = io::loadRgbdFrame(original.frames[i], settings.readerOptions(), i);
    const io::RgbdFrame b = io::loadRgbdFrame(recorded.frames[i], settings.readerOptions(), i);
    EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 0.0) << "colour of frame " << i;
    EXPECT_EQ(cv::countNonZero(a.depth != b.depth), 0) << "depth of frame " << i;
  }
}

// There is no camera on the test machines: asking for one is a clear error, before any frame is read.
TEST(SequenceRunSources, CameraWithoutADeviceIsAClearError) {
  SequenceRunOptions options;
  options.source = FrameSourceKind::kCamera;
  options.camera = "openni2";
  try {
    runSequence(config::loadSettings(kTum2), options);
    FAIL() << "expected a core::Error";
  } catch (const core::Error& e) {
    const std::string what = e.what();
#ifdef AMOS_HAVE_OPENNI2
    EXPECT_NE(what.find("OpenNI2 could not open a device"), std::string::npos) << what;
    EXPECT_NE(what.find("found 0 devices"), std::string::npos) << what;
#else
    EXPECT_NE(what.find("no OpenNI2 support"), std::string::npos) << what;
#endif
  }
}

TEST(SequenceRunSources, CameraSpecNamesDriverAndUri) {
  EXPECT_EQ(parseCameraSpec("openni2").driver, "openni2");
  EXPECT_EQ(parseCameraSpec("openni2").uri, "");
  const CameraSpec c = parseCameraSpec("openni2:1d27/0601@2/5");
  EXPECT_EQ(c.driver, "openni2");
  EXPECT_EQ(c.uri, "1d27/0601@2/5");
  EXPECT_EQ(parseCameraSpec("openni2:/data/a:b.oni").uri, "/data/a:b.oni");
  EXPECT_THROW(parseCameraSpec("kinect"), core::Error);
  EXPECT_EQ(sourceKindName(FrameSourceKind::kRealtime, ""), "realtime");
  EXPECT_EQ(sourceKindName(FrameSourceKind::kCamera, "openni2:x"), "openni2");
}

}  // namespace
}  // namespace amos::run
