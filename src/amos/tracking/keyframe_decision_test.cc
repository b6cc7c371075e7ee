// Step "decide keyframe": each rule on its own, and each toggling the decision from a frame that would make a
// keyframe; the measured inputs (close points, the view change from the reference keyframe) on synthetic frames.
#include "amos/tracking/keyframe_decision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "amos/map/map_point.h"
#include "amos/tracking/step_test_scene.h"

namespace amos::tracking {
namespace {

using step_test::kDeg;
using step_test::poseAt;

// A frame that makes a keyframe by ORB-SLAM2's rules alone: it tracks 100 of the reference keyframe's 200 points
// (under 0.85), not a quarter lost, no close-point shortage, and maxFrames (30) have passed since the last keyframe.
KeyFrameEvidence wanting() {
  KeyFrameEvidence e;
  e.frame = 40;
  e.last_keyframe_frame = 10;
  e.inliers = 100;
  e.reference_tracked = 200;
  e.keyframes_in_map = 5;
  e.close = {150, 20};
  e.mapping_idle = false;
  return e;
}

bool decide(const KeyFrameEvidence& e, const TrackerOptions& o = {}) {
  return wantsKeyFrame(e, map::Frame{}, std::nullopt, o);
}

TEST(KeyFrameDecision, TheReferenceRatioRuleToggles) {
  EXPECT_TRUE(decide(wanting()));
  KeyFrameEvidence e = wanting();
  e.inliers = 171;  // above 0.85 of 200
  EXPECT_FALSE(decide(e));
  e.keyframes_in_map = 1;  // one keyframe: 0.4
  e.inliers = 79;
  EXPECT_TRUE(decide(e));
  e.inliers = 81;
  EXPECT_FALSE(decide(e));
}

TEST(KeyFrameDecision, TooFewTrackedPointsMakeNoKeyFrame) {
  KeyFrameEvidence e = wanting();
  e.inliers = 15;
  e.reference_tracked = 100;
  EXPECT_FALSE(decide(e));
  e.inliers = 16;
  EXPECT_TRUE(decide(e));
}

// Close points: few tracked and many untracked ask for a keyframe however many reference points are tracked.
TEST(KeyFrameDecision, TheClosePointsRuleToggles) {
  KeyFrameEvidence e = wanting();
  e.inliers = 190;
  EXPECT_FALSE(decide(e));
  e.close = {99, 71};
  EXPECT_TRUE(lacksClosePoints(e, TrackerOptions{}));
  EXPECT_TRUE(decide(e));
  e.close = {100, 71};
  EXPECT_FALSE(decide(e));
  e.close = {99, 70};
  EXPECT_FALSE(decide(e));
}

// The timing rules (ORB-SLAM2's c1a-c1c): maxFrames passed, minFrames with mapping idle, or a quarter of the
// reference's points lost.
TEST(KeyFrameDecision, TheTimingRulesToggle) {
  KeyFrameEvidence e = wanting();
  e.frame = 39;  // 29 frames after the last keyframe
  EXPECT_FALSE(decide(e));
  e.mapping_idle = true;
  EXPECT_TRUE(decide(e));
  TrackerOptions min_frames;
  min_frames.min_frames_between_keyframes = 30;
  EXPECT_FALSE(decide(e, min_frames));
  e.mapping_idle = false;
  e.inliers = 49;  // under a quarter of 200
  EXPECT_TRUE(decide(e));
}

TEST(KeyFrameDecision, NoKeyFrameWhileSettlingAfterARelocalisation) {
  KeyFrameEvidence e = wanting();
  e.last_relocalization = 20;  // 20 frames ago, under maxFrames
  EXPECT_TRUE(decide(e));      // a small map (5 keyframes) still takes keyframes
  e.keyframes_in_map = 31;
  EXPECT_FALSE(decide(e));
  e.last_relocalization = 10;  // 30 frames ago
  EXPECT_TRUE(decide(e));
}

TEST(KeyFrameDecision, CountsTheTrackedAndUntrackedClosePoints) {
  step_test::RoomFrames frames;
  map::Frame frame = frames.frame(core::SE3::Identity());
  const map::FrameFeatures& f = *frame.features;
  const double close = frame.sensor->closeDepth();
  int tracked = 0, untracked = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] <= 0 || f.depth[i] >= close) continue;
    if (i % 3 == 0) {  // a match
      frame.map_points[i] = std::make_shared<map::MapPoint>(map::kNoMapPoint, Eigen::Vector3d::Zero(), 0, 0);
      frame.outlier[i] = i % 2 == 0;  // half of them outliers
      (frame.outlier[i] ? untracked : tracked) += 1;
    } else {
      ++untracked;
    }
  }
  ASSERT_GT(tracked, 50);
  const ClosePoints counted = countClosePoints(frame);
  EXPECT_EQ(counted.tracked, tracked);
  EXPECT_EQ(counted.untracked, untracked);
}

// The camera turned 3 deg and moved 6 cm from the reference keyframe: the view change says so, the baseline as a
// share of the frame's median keypoint depth.
TEST(KeyFrameDecision, MeasuresTheViewChangeFromTheReference) {
  step_test::RoomFrames frames;
  const core::SE3 T_rw = poseAt(0.1, 0, 0, 0, 0, 0);
  map::Frame frame = frames.frame(core::SE3::Identity());
  frame.setPose(poseAt(0, 0, 0.06, 0, 3 * kDeg, 0) * T_rw);
  std::vector<float> depths;
  for (const float d : frame.features->depth)
    if (d > 0) depths.push_back(d);
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  const std::optional<ViewChange> view = viewChange(frame, T_rw);
  ASSERT_TRUE(view);
  EXPECT_NEAR(view->rotation_deg, 3, 1e-6);
  EXPECT_NEAR(view->baseline_share, 0.06 / depths[depths.size() / 2], 1e-3);
}

// keyFrameView*: a frame whose timing rules all say no (mapping busy, 10 frames since the last keyframe) makes one
// once the camera has turned 5 deg or moved 5 % of the median depth from its reference keyframe.
TEST(KeyFrameDecision, TheViewRuleToggles) {
  step_test::RoomFrames frames;
  map::Frame frame = frames.frame(core::SE3::Identity());
  KeyFrameEvidence e = wanting();
  e.frame = 20;
  const core::SE3 T_rw = core::SE3::Identity();
  frame.setPose(poseAt(0, 0, 0, 0, 4.9 * kDeg, 0));
  EXPECT_FALSE(wantsKeyFrame(e, frame, T_rw, TrackerOptions{}));
  frame.setPose(poseAt(0, 0, 0, 0, 5.1 * kDeg, 0));
  EXPECT_TRUE(wantsKeyFrame(e, frame, T_rw, TrackerOptions{}));
  TrackerOptions off;
  off.keyframe_view_rotation_deg = 0;
  EXPECT_FALSE(wantsKeyFrame(e, frame, T_rw, off));
  EXPECT_FALSE(wantsKeyFrame(e, frame, std::nullopt, TrackerOptions{}));
  const ViewChange moved{0, 0.051};
  EXPECT_TRUE(viewMovedOn(moved, TrackerOptions{}));
  EXPECT_FALSE(viewMovedOn(ViewChange{0, 0.049}, TrackerOptions{}));
}

// keyFrameMoverShare: movers covering 30 % of the image while the camera is still at the reference's viewpoint
// and tracking is sound: no keyframe; with a smaller mover, a moved camera, unsound tracking or the rule off: one.
TEST(KeyFrameDecision, TheMoversRuleToggles) {
  step_test::RoomFrames frames;
  map::Frame frame = frames.frame(core::SE3::Identity());
  frame.setPose(core::SE3::Identity());
  frame.dynamic_mask = cv::Mat::zeros(480, 640, CV_8UC1);
  frame.dynamic_mask(cv::Rect(0, 0, 640 * 3 / 10, 480)).setTo(255);
  const core::SE3 T_rw = core::SE3::Identity();
  const KeyFrameEvidence e = wanting();  // 100 of 200: sound (a quarter, and closeTrackedMax = 100)
  ASSERT_TRUE(trackingSound(e, TrackerOptions{}));
  EXPECT_FALSE(wantsKeyFrame(e, frame, T_rw, TrackerOptions{}));
  KeyFrameEvidence unsound = e;
  unsound.inliers = 99;
  EXPECT_TRUE(wantsKeyFrame(unsound, frame, T_rw, TrackerOptions{}));
  TrackerOptions off;
  off.keyframe_mover_share = 0;
  EXPECT_TRUE(wantsKeyFrame(e, frame, T_rw, off));
  TrackerOptions larger_share;
  larger_share.keyframe_mover_share = 0.31;
  EXPECT_TRUE(wantsKeyFrame(e, frame, T_rw, larger_share));
  map::Frame turned = frame;
  turned.setPose(poseAt(0, 0, 0, 0, 1.6 * kDeg, 0));
  EXPECT_TRUE(wantsKeyFrame(e, turned, T_rw, TrackerOptions{}));
  map::Frame unmasked = frame;
  unmasked.dynamic_mask = cv::Mat();
  EXPECT_TRUE(wantsKeyFrame(e, unmasked, T_rw, TrackerOptions{}));
}

}  // namespace
}  // namespace amos::tracking
