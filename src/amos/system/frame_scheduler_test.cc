// Stage A: which tasks a mode schedules, the declared dependency of the masked extraction on stage B of the
// previous frame, and that of the corner tracks on stage A of the previous frame.
#include "amos/system/frame_scheduler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::system {
namespace {

using dynamic::DynamicMode;

// A textured frame (random blocks: corners and ORB features everywhere), depth 2 m.
io::RgbdFrame texturedFrame(std::size_t index) {
  io::RgbdFrame f;
  f.index = index;
  cv::Mat small(48, 64, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(small, cv::RNG::UNIFORM, 0, 256);
  cv::resize(small, f.bgr, cv::Size(640, 480), 0, 0, cv::INTER_NEAREST);
  f.depth = cv::Mat(480, 640, CV_32F, cv::Scalar(2.0f));
  return f;
}

TEST(StageATasks, EachModeSchedulesItsTasks) {
  dynamic::DynamicOptions o;
  o.mode = DynamicMode::kNone;
  StageATasks t = StageATasks::forMode(o);
  EXPECT_FALSE(t.segmentation || t.geometry || t.masked_extraction);
  o.mode = DynamicMode::kPrior;
  t = StageATasks::forMode(o);
  EXPECT_TRUE(t.segmentation && t.masked_extraction && !t.geometry);
  o.mode = DynamicMode::kGeometry;
  t = StageATasks::forMode(o);
  EXPECT_TRUE(t.geometry && !t.segmentation && !t.masked_extraction);
  o.mode = DynamicMode::kFull;
  t = StageATasks::forMode(o);
  EXPECT_TRUE(t.geometry && t.segmentation && t.masked_extraction);
}

// Frame 1's preparation waits for frame 0's dilated person mask (declared hand-off), then detects ORB features only
// outside it when it covers at least Dynamic.priorMaskedExtractionCoverage of the view.
TEST(FrameScheduler, MaskedExtractionWaitsForThePreviousFramesMask) {
  const feature::OrbExtractor orb(feature::OrbOptions{});
  dynamic::DynamicOptions options;
  options.mode = DynamicMode::kGeometry;  // no segmenter needed; the dependency is what is tested
  StageATasks tasks = StageATasks::forMode(options);
  tasks.masked_extraction = true;
  // Drive extractFeatures through a promise, as the scheduler wires it.
  std::promise<cv::Mat> mask0;
  std::promise<bool> map_ready;
  PreparationInputs inputs{mask0.get_future().share(), map_ready.get_future().share()};
  core::SerialExecutor lane;
  const io::RgbdFrame frame = texturedFrame(1);
  const FrameMotionInput motion = prepareMotion(frame, tasks, options);
  EXPECT_FALSE(motion.pyramid.empty());
  EXPECT_FALSE(motion.corners.empty());
  auto prepared = lane.submit([&] { return extractFeatures(motion.gray, tasks, options, orb, inputs); });
  EXPECT_EQ(prepared.wait_for(std::chrono::milliseconds(300)), std::future_status::timeout)
      << "the preparation did not wait for the previous frame's mask";
  cv::Mat left(480, 640, CV_8U, cv::Scalar(0));
  left.colRange(0, 448).setTo(255);  // 70 % of the view
  mask0.set_value(left);
  map_ready.set_value(true);
  const SlotOrbFeatures p = prepared.get();
  ASSERT_GT(p.features.keypoints.size(), 50u);
  for (const cv::KeyPoint& k : p.features.keypoints) EXPECT_GE(k.pt.x, 448.f - 1.f) << "a keypoint inside the mask";
}

// Mode geometry: no segmentation lane; slots are found by number until released; at most kMaxAhead wait.
TEST(FrameScheduler, SlotsByNumber) {
  dynamic::DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  FrameScheduler scheduler(feature::OrbOptions{}, options, nullptr);
  EXPECT_EQ(scheduler.push(texturedFrame(10), 0), 0u);
  EXPECT_EQ(scheduler.push(texturedFrame(11), 0), 1u);
  EXPECT_EQ(scheduler.slot(1).frame.index, 11u);
  EXPECT_FALSE(scheduler.slot(0).segmentation.valid());
  EXPECT_FALSE(scheduler.slot(0).features.get().features.keypoints.empty());  // frame 0 needs no hand-off
  EXPECT_FALSE(scheduler.slot(0).partition.get().partition.segmentation.superpixels.empty());
  EXPECT_FALSE(scheduler.slot(0).motion.get().pyramid.empty());
  scheduler.release(1);
  EXPECT_THROW(scheduler.slot(0), core::Error);
  EXPECT_EQ(scheduler.slot(1).frame.index, 11u);
  // The destructor must not hang on slot 1's preparation (it has no hand-off to wait for here) nor on others.
}

// The corner tracks are a stage-A task of the later frame: frame 0 has none, frame 1 gets frame 0's corners tracked
// into it, exactly what tracking them from the two frames' motion inputs gives; in mode none nothing is tracked.
TEST(FrameScheduler, CornerTracksComeFromTheFramePushedBefore) {
  dynamic::DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  FrameScheduler scheduler(feature::OrbOptions{}, options, nullptr);
  scheduler.push(texturedFrame(0), 0);
  io::RgbdFrame shifted = texturedFrame(1);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 3, 0, 1, 2);  // the view moved by (3, 2) px
  cv::warpAffine(shifted.bgr, shifted.bgr, shift, shifted.bgr.size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  scheduler.push(shifted, 0);
  EXPECT_FALSE(scheduler.slot(0).corner_tracks.get().made);
  const FrameCornerTracks tracks = scheduler.slot(1).corner_tracks.get();
  ASSERT_TRUE(tracks.made);
  ASSERT_GT(tracks.tracks.size(), 20u);
  const std::vector<dynamic::PointTrack> direct =
      dynamic::trackPoints({scheduler.slot(0).motion.get().pyramid, scheduler.slot(1).motion.get().pyramid},
                           scheduler.slot(0).motion.get().corners, options.tracking);
  ASSERT_EQ(tracks.tracks.size(), direct.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    EXPECT_EQ(tracks.tracks[i].current, direct[i].current);
    EXPECT_EQ(tracks.tracks[i].source_index, direct[i].source_index);
  }
  EXPECT_NEAR(tracks.tracks[0].current.x - tracks.tracks[0].last.x, 3.0, 0.5);
  EXPECT_NEAR(tracks.tracks[0].current.y - tracks.tracks[0].last.y, 2.0, 0.5);

  options.mode = DynamicMode::kNone;
  FrameScheduler plain(feature::OrbOptions{}, options, nullptr);
  plain.push(texturedFrame(0), 0);
  plain.push(texturedFrame(1), 0);
  EXPECT_FALSE(plain.slot(1).corner_tracks.get().made);
}

TEST(FrameScheduler, ModesThatSegmentNeedASegmenter) {
  dynamic::DynamicOptions options;
  options.mode = DynamicMode::kFull;
  EXPECT_THROW(FrameScheduler(feature::OrbOptions{}, options, nullptr), core::Error);
}

}  // namespace
}  // namespace amos::system
