// The public API against a caller's mistakes (issue 51): every argument checked and named, frames submitted before
// finish() kept, a bad frame of a folder skipped, calls from two threads serialised, moved-from objects that say so.
// Short synthetic sequences in mode geometry (no models needed).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <thread>

#include "amos/sequence_folder.h"
#include "amos/slam.h"
#include "amos/synth/sequence.h"
#include "amos/testing/error_of.h"
#include "amos/testing/scratch_dir.h"

namespace amos {
namespace {

namespace fs = std::filesystem;

std::string sequence(int frames) {
  return synth::cachedSequence((fs::path(AMOS_BINARY_DIR) / "test_outputs" / "api_sequences").string(),
                               "walking_xyz", 1, frames);
}

Options geometryOptions() {
  Options o;
  o.settings_file = std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml";
  o.mode = Mode::kGeometry;
  o.deterministic = true;
  return o;
}

using amos::testing::errorOf;

#define EXPECT_ERROR_NAMES(call, words) \
  EXPECT_NE(errorOf([&] { call; }).find(words), std::string::npos) << "message: " << errorOf([&] { call; })

TEST(SlamMisuse, FramesSubmittedBeforeFinishReachTheTrajectory) {
  const SequenceFolder folder(sequence(30));
  Slam slam(geometryOptions());
  for (std::size_t i = 0; i < 3; ++i) {
    const RgbdImages f = folder.read(i);
    slam.submit(f.bgr, f.depth, f.timestamp);
  }
  slam.finish();
  EXPECT_EQ(slam.pending(), 0u);
  EXPECT_EQ(slam.trajectory().size(), 3u);
  EXPECT_EQ(slam.summary().frames, 3u);
}

TEST(SlamMisuse, TimeStampsMustBeFiniteAndIncrease) {
  const SequenceFolder folder(sequence(30));
  Slam slam(geometryOptions());
  const RgbdImages f = folder.read(0), g = folder.read(1);
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()})
    EXPECT_ERROR_NAMES(slam.track(f.bgr, f.depth, bad), "argument 'timestamp' must be finite");
  slam.track(f.bgr, f.depth, f.timestamp);
  EXPECT_ERROR_NAMES(slam.track(g.bgr, g.depth, f.timestamp), "argument 'timestamp' must increase");
  EXPECT_ERROR_NAMES(slam.submit(g.bgr, g.depth, f.timestamp - 1), "argument 'timestamp' must increase");
  slam.track(g.bgr, g.depth, g.timestamp);
  slam.finish();
  const std::vector<StampedPose> poses = slam.trajectory();
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].timestamp, f.timestamp);
  EXPECT_EQ(poses[1].timestamp, g.timestamp);
}

TEST(SlamMisuse, EveryImageArgumentIsCheckedAndNamed) {
  const SequenceFolder folder(sequence(30));
  Slam slam(geometryOptions());
  const RgbdImages f = folder.read(0);
  const double t = f.timestamp;
  EXPECT_ERROR_NAMES(slam.track(cv::Mat(), f.depth, t), "argument 'bgr' is empty");
  EXPECT_ERROR_NAMES(slam.track(cv::Mat(480, 640, CV_8UC1), f.depth, t), "argument 'bgr' must be CV_8UC3 (8-bit "
                                                                          "BGR), got CV_8UC1");
  EXPECT_ERROR_NAMES(slam.track(cv::Mat(480, 640, CV_8UC4), f.depth, t), "got CV_8UC4");
  EXPECT_ERROR_NAMES(slam.track(cv::Mat(240, 320, CV_8UC3), f.depth, t), "argument 'bgr' is 320x240");
  EXPECT_ERROR_NAMES(slam.track(f.bgr, cv::Mat(), t), "argument 'depth' is empty");
  EXPECT_ERROR_NAMES(slam.track(f.bgr, cv::Mat(480, 640, CV_8UC1), t), "argument 'depth' must be CV_16UC1");
  EXPECT_ERROR_NAMES(slam.track(f.bgr, cv::Mat(480, 640, CV_16UC3), t), "got CV_16UC3");
  EXPECT_ERROR_NAMES(slam.track(f.bgr, cv::Mat(480, 640, CV_64FC1), t), "got CV_64FC1");
  EXPECT_ERROR_NAMES(slam.track(f.bgr, cv::Mat(479, 640, CV_16UC1), t), "argument 'depth' is 640x479");
  EXPECT_ERROR_NAMES(slam.track(f.bgr, f.depth, t, cv::Mat(480, 640, CV_8UC3)), "argument 'prior_mask' must be "
                                                                                 "CV_8UC1");
  EXPECT_ERROR_NAMES(slam.track(f.bgr, f.depth, t, cv::Mat(480, 641, CV_8UC1)), "argument 'prior_mask' is 641x480");
  EXPECT_EQ(slam.summary().frames, 0u);  // nothing was taken
  // Views into larger images (not contiguous) are fine: the library copies what it keeps.
  cv::Mat wide_bgr(480, 700, CV_8UC3), wide_depth(480, 700, CV_16UC1);
  f.bgr.copyTo(wide_bgr(cv::Rect(30, 0, 640, 480)));
  f.depth.copyTo(wide_depth(cv::Rect(30, 0, 640, 480)));
  const FrameResult r = slam.track(wide_bgr(cv::Rect(30, 0, 640, 480)), wide_depth(cv::Rect(30, 0, 640, 480)), t);
  EXPECT_EQ(r.state, TrackingState::kOk);
  EXPECT_EQ(slam.imageSize(), cv::Size(640, 480));
}

// A second thread's calls wait for the first's: its next() never takes a frame that track() submitted (before the
// mutex, the two raced in the pipeline: std::future_error, or a frame taken twice).
TEST(SlamMisuse, CallsFromTwoThreadsAreSerialised) {
  const SequenceFolder folder(sequence(30));
  std::vector<RgbdImages> frames;
  for (std::size_t i = 0; i < folder.size(); ++i) frames.push_back(folder.read(i));
  Slam slam(geometryOptions());
  std::atomic<bool> done{false};
  std::atomic<int> other_errors{0}, stolen{0};
  std::thread other([&] {
    while (!done) {
      try {
        slam.next();
        ++stolen;
      } catch (const std::runtime_error& e) {
        if (std::string(e.what()).find("no frame was submitted") == std::string::npos) ++other_errors;
      } catch (...) {
        ++other_errors;
      }
      slam.summary();
      slam.trajectory();
      slam.keyFrames();
      std::this_thread::yield();
    }
  });
  std::size_t in_order = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    try {
      in_order += slam.track(frames[i].bgr, frames[i].depth, frames[i].timestamp).frame == i;
    } catch (...) {
    }
  }
  done = true;
  other.join();
  EXPECT_EQ(in_order, frames.size());
  EXPECT_EQ(stolen.load(), 0);
  EXPECT_EQ(other_errors.load(), 0);
}

TEST(SlamMisuse, AMovedFromSlamSaysSo) {
  const SequenceFolder folder(sequence(30));
  const RgbdImages f = folder.read(0);
  Slam slam(geometryOptions());
  Slam moved(std::move(slam));
  const std::function<void()> calls[] = {
      [&] { slam.track(f.bgr, f.depth, f.timestamp); },
      [&] { slam.submit(f.bgr, f.depth, f.timestamp); },
      [&] { slam.next(); },
      [&] { slam.pending(); },
      [&] { slam.trackFrames([] { return std::optional<InputFrame>(); }, nullptr); },
      [&] { slam.loadMap("x.amap"); },
      [&] { slam.finish(); },
      [&] { slam.finished(); },
      [&] { slam.saveMap("x.amap"); },
      [&] { slam.trajectory(); },
      [&] { slam.writeTrajectory("x.txt"); },
      [&] { slam.keyFrames(); },
      [&] { slam.takeKeyFrameEvents(); },
      [&] { slam.mapPoints(); },
      [&] { slam.summary(); },
      [&] { slam.imageSize(); },
  };
  for (const auto& call : calls) EXPECT_NE(errorOf(call).find("this Slam was moved from"), std::string::npos);
  EXPECT_EQ(moved.track(f.bgr, f.depth, f.timestamp).state, TrackingState::kOk);
  // Assigned over: the Slam it held is finished first, and the assigned one works.
  Slam other(geometryOptions());
  other = std::move(moved);
  EXPECT_EQ(other.summary().frames, 1u);
}

TEST(SlamMisuse, AMovedFromSequenceFolderSaysSo) {
  SequenceFolder folder(sequence(30));
  SequenceFolder moved(std::move(folder));
  const std::function<void()> calls[] = {
      [&] { folder.size(); },   [&] { folder.read(0); }, [&] { folder.next(); },
      [&] { folder.skipped(); }, [&] { folder.groundTruthFile(); }, [&] { folder.dir(); },
  };
  for (const auto& call : calls)
    EXPECT_NE(errorOf(call).find("this SequenceFolder was moved from"), std::string::npos);
  EXPECT_EQ(moved.size(), 30u);
}

// As `amos-slam run` over a folder: a damaged frame is skipped (warned about, counted), the stream goes on.
TEST(SlamMisuse, ASequenceFolderSkipsABadFrameAndGoesOn) {
  const fs::path dir = testing::scratchDirForThisTest("amos_api_") / "seq";
  fs::copy(sequence(30), dir, fs::copy_options::recursive);
  const SequenceFolder original(dir.string());
  const std::string damaged = original.read(5).rgb_file, not_depth = original.read(9).depth_file;
  std::ofstream(damaged, std::ios::binary | std::ios::trunc) << "not a png";
  fs::copy_file(original.read(9).rgb_file, not_depth, fs::copy_options::overwrite_existing);  // 8-bit colour
  SequenceFolder folder(dir.string());
  std::vector<double> stamps;
  while (const std::optional<RgbdImages> f = folder.next()) stamps.push_back(f->timestamp);
  EXPECT_EQ(stamps.size(), 28u);
  EXPECT_EQ(folder.skipped(), 2u);
  EXPECT_EQ(stamps[5], original.read(6).timestamp);
  EXPECT_THROW(folder.read(5), std::runtime_error);  // asked for by number, it is an error naming the file
  EXPECT_NE(errorOf([&] { folder.read(5); }).find(damaged), std::string::npos);
}

}  // namespace
}  // namespace amos
