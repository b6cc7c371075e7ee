// The public API (include/amos/slam.h) on short synthetic sequences (mode geometry: no models needed): the same
// trajectory as a run of the same folder (the same engine), its errors, maps and keyframe events.
#include "amos/slam.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "amos/config/settings.h"
#include "amos/run/sequence_run.h"
#include "amos/sequence_folder.h"
#include "amos/synth/sequence.h"
#include "amos/testing/file_text.h"
#include "amos/testing/scratch_dir.h"
#include "amos/testing/test_inputs.h"

namespace amos {
namespace {

namespace fs = std::filesystem;

using amos::testing::kTum3;


std::string sequence(const std::string& preset, int frames) {
  return synth::cachedSequence((fs::path(AMOS_BINARY_DIR) / "test_outputs" / "api_sequences").string(), preset, 1,
                               frames);
}

Options slamGeometryOptions() {
  Options o;
  o.settings_file = kTum3;
  o.mode = Mode::kGeometry;
  o.deterministic = true;
  return o;
}

void trackAll(Slam& slam, const SequenceFolder& folder) {
  for (std::size_t i = 0; i < folder.size(); ++i) {
    const RgbdImages f = folder.read(i);
    slam.track(f.bgr, f.depth, f.timestamp);
  }
}

// The API and `amos-slam run` share the engine: in deterministic mode the same folder gives the same trajectory
// file, byte for byte, though the run reads ahead and the API takes one frame at a time.
TEST(SlamApi, TrajectoryIsTheRunsByteForByte) {
  const std::string seq = sequence("walking_xyz", 30);
  const fs::path dir = testing::scratchDirForThisTest("amos_api_");
  run::SequenceRunOptions run_options;
  run_options.sequence_dir = seq;
  run_options.mode = "geometry";
  run_options.deterministic = true;
  const run::SequenceRunResult run = run::runSequence(config::loadSettings(kTum3), run_options);
  io::writeTumTrajectory((dir / "run.txt").string(), run.trajectory);

  Slam slam(slamGeometryOptions());
  const SequenceFolder folder(seq);
  std::size_t ok = 0;
  for (std::size_t i = 0; i < folder.size(); ++i) {
    const RgbdImages f = folder.read(i);
    const FrameResult r = slam.track(f.bgr, f.depth, f.timestamp);
    EXPECT_EQ(r.frame, i);
    EXPECT_EQ(r.dynamic_mask.type(), CV_8UC1);
    EXPECT_EQ(r.dynamic_mask.size(), f.bgr.size());
    ok += r.state == TrackingState::kOk;
  }
  slam.finish();
  slam.writeTrajectory((dir / "api.txt").string());
  EXPECT_EQ(ok, 30u);
  EXPECT_EQ(slam.trajectory().size(), 30u);
  EXPECT_GT(testing::fileText(dir / "run.txt").size(), 1000u);
  EXPECT_EQ(testing::fileText(dir / "api.txt"), testing::fileText(dir / "run.txt"));
}

// T_wc maps camera points into the world: the last pose is near the ground truth's relative motion, and its
// inverse relation to the frame result holds (the first frame is the world's origin).
TEST(SlamApi, FirstPoseIsTheOriginAndPosesAreRigid) {
  Slam slam(slamGeometryOptions());
  const SequenceFolder folder(sequence("walking_xyz", 30));
  const RgbdImages first = folder.read(0);
  const FrameResult r0 = slam.track(first.bgr, first.depth, first.timestamp);
  EXPECT_EQ(r0.state, TrackingState::kOk);
  ASSERT_TRUE(r0.T_wc);
  EXPECT_TRUE(r0.T_wc->isApprox(Eigen::Matrix4d::Identity(), 1e-12));
  const RgbdImages second = folder.read(1);
  const FrameResult r1 = slam.track(second.bgr, second.depth, second.timestamp);
  ASSERT_TRUE(r1.T_wc);
  const Eigen::Matrix3d R = r1.T_wc->topLeftCorner<3, 3>();
  EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
  EXPECT_EQ(r1.T_wc->row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

TEST(SlamApi, BadFramesAndCallsOutOfOrderAreClearErrors) {
  Slam slam(slamGeometryOptions());
  const SequenceFolder folder(sequence("walking_xyz", 30));
  const RgbdImages f = folder.read(0);
  cv::Mat small;
  cv::resize(f.bgr, small, cv::Size(320, 240));
  try {
    slam.track(small, f.depth, 0);
    FAIL() << "a frame of the wrong size was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("argument 'bgr' is 320x240, the settings say 640x480"), std::string::npos)
        << e.what();
  }
  cv::Mat grey(480, 640, CV_8UC1, cv::Scalar(100));
  EXPECT_THROW(slam.track(grey, f.depth, 0), std::runtime_error);
  cv::Mat depth_u8(480, 640, CV_8UC1, cv::Scalar(1));
  EXPECT_THROW(slam.track(f.bgr, depth_u8, 0), std::runtime_error);
  slam.track(f.bgr, f.depth, f.timestamp);
  EXPECT_THROW(slam.loadMap("/nonexistent.map"), std::runtime_error);  // after the first frame
  slam.finish();
  slam.finish();  // idempotent
  EXPECT_THROW(slam.track(f.bgr, f.depth, f.timestamp + 1), std::runtime_error);

  Options no_settings;
  EXPECT_THROW(Slam{no_settings}, std::runtime_error);
  Options missing = slamGeometryOptions();
  missing.settings_file = "/nonexistent/settings.yaml";
  EXPECT_THROW(Slam{missing}, std::runtime_error);
  Options localize = slamGeometryOptions();
  localize.localization_only = true;
  Slam without_map(localize);
  EXPECT_THROW(without_map.track(f.bgr, f.depth, f.timestamp), std::runtime_error);
}

// Depth as CV_32F metres gives the same trajectory as the raw CV_16U values it came from; the inputs are not
// written.
TEST(SlamApi, DepthInMetresEqualsRawDepthAndInputsAreUnchanged) {
  const SequenceFolder folder(sequence("walking_xyz", 30));
  Slam raw(slamGeometryOptions()), metres(slamGeometryOptions());
  for (std::size_t i = 0; i < 10; ++i) {
    const RgbdImages f = folder.read(i);
    const cv::Mat bgr_before = f.bgr.clone(), depth_before = f.depth.clone();
    const FrameResult a = raw.track(f.bgr, f.depth, f.timestamp);
    cv::Mat depth_m;
    f.depth.convertTo(depth_m, CV_32F, 1.0 / 5000.0);
    const FrameResult b = metres.track(f.bgr, depth_m, f.timestamp);
    ASSERT_TRUE(a.T_wc && b.T_wc) << "frame " << i;
    EXPECT_EQ(*a.T_wc, *b.T_wc) << "frame " << i;
    EXPECT_EQ(cv::norm(f.bgr, bgr_before, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(f.depth, depth_before, cv::NORM_INF), 0.0);
  }
}

// Keyframes reach the callback (mapping thread) and the polling call alike, and the saved map localises a second
// pass over the sequence without growing.
TEST(SlamApi, KeyFrameEventsAndMapsRoundTrip) {
  const fs::path dir = testing::scratchDirForThisTest("amos_api_");
  const SequenceFolder folder(sequence("walking_xyz", 30));
  std::atomic<int> callbacks{0};
  Options o = slamGeometryOptions();
  o.on_keyframe = [&](const KeyFrameEvent&) { ++callbacks; };
  Slam slam(o);
  trackAll(slam, folder);
  slam.finish();
  const std::vector<KeyFrameEvent> events = slam.takeKeyFrameEvents();
  EXPECT_GE(events.size(), 2u);
  EXPECT_EQ(callbacks.load(), static_cast<int>(events.size()));
  EXPECT_TRUE(slam.takeKeyFrameEvents().empty());
  const MapSummary saved = slam.summary();
  EXPECT_EQ(saved.frames, 30u);
  EXPECT_GT(saved.map_points, 100u);
  EXPECT_EQ(slam.mapPoints().size(), saved.map_points);
  EXPECT_EQ(slam.keyFrames().size(), saved.keyframes);
  slam.saveMap((dir / "map.amap").string());

  Options again = slamGeometryOptions();
  again.map_file = (dir / "map.amap").string();
  again.localization_only = true;
  Slam localizer(again);
  trackAll(localizer, folder);
  localizer.finish();
  EXPECT_EQ(localizer.summary().keyframes, saved.keyframes);
  EXPECT_GT(localizer.trajectory().size(), 25u);

  Options via_call = slamGeometryOptions();
  via_call.localization_only = true;
  Slam loaded(via_call);
  loaded.loadMap((dir / "map.amap").string());
  const RgbdImages f = folder.read(5);
  EXPECT_EQ(loaded.track(f.bgr, f.depth, f.timestamp).state, TrackingState::kOk);
}

// submit() ahead of next() (up to kMaxPending frames) gives track()'s results; more waiting frames, or next()
// with none, are errors.
TEST(SlamApi, SubmittingAheadGivesTrackResults) {
  const SequenceFolder folder(sequence("walking_xyz", 30));
  Slam one(slamGeometryOptions()), ahead(slamGeometryOptions());
  for (std::size_t i = 0; i < 12; ++i) {
    const RgbdImages f = folder.read(i);
    one.track(f.bgr, f.depth, f.timestamp);
  }
  std::size_t read = 0;
  std::vector<FrameResult> results;
  while (read < 12 || ahead.pending() > 0) {
    while (read < 12 && ahead.pending() < Slam::kMaxPending) {
      const RgbdImages f = folder.read(read++);
      ahead.submit(f.bgr, f.depth, f.timestamp);
    }
    if (read == Slam::kMaxPending) {
      const RgbdImages f = folder.read(read);
      EXPECT_THROW(ahead.submit(f.bgr, f.depth, f.timestamp), std::runtime_error);
    }
    results.push_back(ahead.next());
  }
  EXPECT_THROW(ahead.next(), std::runtime_error);
  one.finish();
  ahead.finish();
  ASSERT_EQ(results.size(), 12u);
  for (std::size_t i = 0; i < results.size(); ++i) EXPECT_EQ(results[i].frame, i);
  const std::vector<StampedPose> a = one.trajectory(), b = ahead.trajectory();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].T_wc, b[i].T_wc) << i;
}

TEST(SlamApi, SettingsFromTextAndVersion) {
  std::ifstream in(kTum3);
  std::stringstream ss;
  ss << in.rdbuf();
  Options o;
  o.settings_yaml = ss.str();
  o.mode = Mode::kNone;
  Slam slam(o);
  const RgbdImages f = SequenceFolder(sequence("walking_xyz", 30)).read(0);
  EXPECT_EQ(slam.track(f.bgr, f.depth, f.timestamp).state, TrackingState::kOk);
  EXPECT_STREQ(kVersion, AMOS_VERSION);
  EXPECT_STREQ(toString(TrackingState::kLost), "lost");
}

TEST(SequenceFolder, ReadsTheRunsFramesAndNamesWhatIsWrong) {
  const SequenceFolder folder(sequence("walking_xyz", 30));
  ASSERT_EQ(folder.size(), 30u);
  const RgbdImages f = folder.read(3);
  EXPECT_EQ(f.bgr.type(), CV_8UC3);
  EXPECT_EQ(f.depth.type(), CV_16UC1);
  EXPECT_GT(f.timestamp, 0);
  EXPECT_FALSE(folder.groundTruthFile().empty());
  EXPECT_THROW(folder.read(30), std::runtime_error);
  SequenceFolder streamed(sequence("walking_xyz", 30));
  for (std::size_t i = 0; i < 30; ++i) {
    const std::optional<RgbdImages> g = streamed.next();
    ASSERT_TRUE(g) << i;
    const RgbdImages r = folder.read(i);
    EXPECT_EQ(g->timestamp, r.timestamp);
    EXPECT_EQ(cv::norm(g->bgr, r.bgr, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(g->depth, r.depth, cv::NORM_INF), 0.0);
  }
  EXPECT_FALSE(streamed.next());
  EXPECT_FALSE(streamed.next());
  SequenceFolder abandoned(sequence("walking_xyz", 30));  // destroyed with frames still queued
  EXPECT_TRUE(abandoned.next());
  EXPECT_THROW(SequenceFolder("/nonexistent/sequence"), std::runtime_error);
}

// A ".bag" path: read by a library with the ROS part (src/amos/rosbag/sequence_folder_bag_test.cc), else refused
// with an error naming it; either way the error names the bag.
TEST(SequenceFolder, ABagPathIsReadOrRefusedNamingIt) {
  const std::string bag = "/nonexistent/recording.bag";
  try {
    SequenceFolder folder(bag);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string expected = bagReadingAvailable()
                                     ? "bag '" + bag + "' cannot be read"
                                     : "'" + bag + "' is a ROS 1 bag, and this library was built without the ROS part";
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(SequenceFolder, AFolderRefusesTheBagOptions) {
  SequenceOptions options;
  options.groundtruth_topic = "/tf";
  try {
    SequenceFolder folder(sequence("walking_xyz", 30), options);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("amos::SequenceOptions::groundtruth_topic '/tf': only for a bag"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace amos
