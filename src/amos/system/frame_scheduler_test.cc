// Stage A: which tasks a mode schedules, and the declared dependency of the masked extraction on stage B of the
// previous frame.
#include "amos/system/frame_scheduler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"
#include "amos/testing/test_camera.h"

namespace amos::system {
namespace {

using dynamic::DynamicMode;

SlamOptions testOptions() {
  SlamOptions o;
  o.camera = testing::testIntrinsics();
  o.sensor.bf = 40.0;
  o.sensor.th_depth = 40.0;
  o.deterministic = true;
  return o;
}

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
  o.judge_prior_regions = true;  // a person may turn out static: the mask must not keep features away from it
  EXPECT_FALSE(StageATasks::forMode(o).masked_extraction);
}

// Frame 1's preparation waits for frame 0's dilated person mask (declared hand-off), then detects ORB features only
// outside it when it covers at least Dynamic.priorMaskedExtractionCoverage of the view.
TEST(FrameScheduler, MaskedExtractionWaitsForThePreviousFramesMask) {
  SlamSystem slam(testOptions());
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
  auto prepared = lane.submit([&] { return extractFeatures(motion.gray, tasks, options, slam, inputs); });
  EXPECT_EQ(prepared.wait_for(std::chrono::milliseconds(300)), std::future_status::timeout)
      << "the preparation did not wait for the previous frame's mask";
  cv::Mat left(480, 640, CV_8U, cv::Scalar(0));
  left.colRange(0, 448).setTo(255);  // 70 % of the view
  mask0.set_value(left);
  map_ready.set_value(true);
  const FrameFeatures p = prepared.get();
  ASSERT_GT(p.features.keypoints.size(), 50u);
  for (const cv::KeyPoint& k : p.features.keypoints) EXPECT_GE(k.pt.x, 448.f - 1.f) << "a keypoint inside the mask";
}

// Mode geometry: no segmentation lane; slots are found by number until released; at most kMaxAhead wait.
TEST(FrameScheduler, SlotsByNumber) {
  SlamSystem slam(testOptions());
  dynamic::DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  FrameScheduler scheduler(slam, options, nullptr);
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

TEST(FrameScheduler, ModesThatSegmentNeedASegmenter) {
  SlamSystem slam(testOptions());
  dynamic::DynamicOptions options;
  options.mode = DynamicMode::kFull;
  EXPECT_THROW(FrameScheduler(slam, options, nullptr), core::Error);
}

}  // namespace
}  // namespace amos::system
