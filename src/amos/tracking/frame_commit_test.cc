// Step "commit": the velocity after a frame, the matches kept, the pose relative to the reference keyframe, and the
// keyframe made from a frame with its new points.
#include "amos/tracking/frame_commit.h"

#include <gtest/gtest.h>

#include <shared_mutex>

#include "amos/map/map_point.h"
#include "amos/testing/pose_matchers.h"
#include "amos/tracking/keyframe_insertion.h"
#include "amos/tracking/step_test_scene.h"

namespace amos::tracking {
namespace {

using amos::testing::PoseNear;
using step_test::kDeg;
using step_test::poseAt;

TEST(FrameCommit, TheVelocityIsTheMotionFromTheLastTrackedFrame) {
  MotionStep step;
  step.tracked = true;
  step.last_tracked = true;
  step.last_T_cw = poseAt(0.1, 0.2, 0.3, 0.01, 0.02, 0.03);
  const core::SE3 motion = poseAt(0.02, 0, 0.01, 0, 0.5 * kDeg, 0);
  step.T_cw = motion * step.last_T_cw;
  const std::optional<core::SE3> old = poseAt(0.5, 0, 0, 0, 0, 0);
  const std::optional<core::SE3> v = nextVelocity(old, step);
  ASSERT_TRUE(v);
  EXPECT_THAT(*v, PoseNear(motion, 1e-12, 1e-12));
  MotionStep relocalized = step;
  relocalized.relocalized = true;
  EXPECT_FALSE(nextVelocity(old, relocalized));
  MotionStep lost = step;
  lost.tracked = false;
  EXPECT_FALSE(nextVelocity(old, lost));
  MotionStep after_loss = step;  // tracked again without relocalisation: nothing to measure, the old one stays
  after_loss.last_tracked = false;
  ASSERT_TRUE(nextVelocity(old, after_loss));
  EXPECT_THAT(*nextVelocity(old, after_loss), PoseNear(*old, 1e-12, 1e-12));
}

TEST(FrameCommit, DropsTemporaryAndOutlierMatches) {
  step_test::RoomFrames frames;
  map::Frame frame = frames.frame(core::SE3::Identity());
  auto in_map = std::make_shared<map::MapPoint>(1, Eigen::Vector3d(0, 0, 2), 0, 0);
  in_map->addObservation(0, 0, true);
  auto temporary = std::make_shared<map::MapPoint>(map::kNoMapPoint, Eigen::Vector3d(0, 0, 2), map::kNoKeyFrame, 0);
  frame.map_points[0] = in_map;
  frame.map_points[1] = temporary;
  frame.map_points[2] = in_map;
  frame.outlier[2] = true;
  dropTemporaryMatches(frame);
  EXPECT_EQ(frame.map_points[0], in_map);
  EXPECT_FALSE(frame.map_points[1]);
  EXPECT_EQ(frame.map_points[2], in_map);
  dropOutlierMatches(frame);
  EXPECT_EQ(frame.map_points[0], in_map);
  EXPECT_FALSE(frame.map_points[2]);
  EXPECT_FALSE(frame.outlier[2]);
}

// A keyframe at T_kw: a tracked frame keeps T_cr = T_cw * T_kw^-1 (the identity when it is the keyframe); a lost
// frame keeps the last T_cr and takes its pose from the keyframe's current pose (moved by bundle adjustment here).
TEST(FrameCommit, AnchorsTheFrameToItsReferenceKeyFrame) {
  step_test::RoomFrames frames;
  map::Frame first = frames.frame(core::SE3::Identity());
  const core::SE3 T_kw = poseAt(0.1, 0, 0, 0, 2 * kDeg, 0);
  const step_test::MapFromFrame m = step_test::mapFrom(first, T_kw);
  std::shared_lock lock(m.map->mutex());
  map::Frame frame = frames.frame(core::SE3::Identity());
  const core::SE3 T_ck = poseAt(0.03, 0.01, 0, 0, 1 * kDeg, 0);
  frame.setPose(T_ck * T_kw);
  ReferenceAnchoring tracked;
  tracked.tracked = true;
  tracked.reference_kf = m.kf->id();
  EXPECT_THAT(anchorToReference(frame, tracked, *m.map), PoseNear(T_ck, 1e-9, 1e-9));
  EXPECT_EQ(frame.reference_kf, m.kf->id());
  tracked.own_keyframe = true;
  EXPECT_THAT(anchorToReference(frame, tracked, *m.map), PoseNear(core::SE3::Identity(), 1e-12, 1e-12));

  const core::SE3 moved = poseAt(0, 0.05, 0, 0, 0, 0) * T_kw;
  m.kf->setPose(moved);
  map::Frame lost_frame = frames.frame(core::SE3::Identity());
  ReferenceAnchoring lost;
  lost.last_reference_kf = m.kf->id();
  lost.last_T_cr = T_ck;
  EXPECT_THAT(anchorToReference(lost_frame, lost, *m.map), PoseNear(T_ck, 1e-12, 1e-12));
  EXPECT_EQ(lost_frame.reference_kf, m.kf->id());
  EXPECT_THAT(lost_frame.T_cw, PoseNear(T_ck * moved, 1e-9, 1e-9));
  map::Frame never_tracked = frames.frame(core::SE3::Identity());
  anchorToReference(never_tracked, ReferenceAnchoring{}, *m.map);
  EXPECT_EQ(never_tracked.reference_kf, map::kNoKeyFrame);
}

// A keyframe from a frame matched to the first keyframe's points: the matches become its observations, and its
// unmatched keypoints with depth become points at their depth, closest first (all close ones, at least
// newPointsMin).
TEST(KeyFrameInsertion, ObservesTheMatchesAndAddsPointsFromDepth) {
  step_test::RoomFrames frames;
  map::Frame first = frames.frame(core::SE3::Identity());
  const step_test::MapFromFrame m = step_test::mapFrom(first, core::SE3::Identity());
  map::Frame frame = frames.frame(core::SE3::Identity());
  frame.setPose(core::SE3::Identity());
  // The same view: keypoint i of both frames is the same feature; match every other one.
  int matched = 0;
  for (std::size_t i = 0; i < frame.size(); i += 2) {
    if (!first.map_points[i]) continue;
    frame.map_points[i] = first.map_points[i];
    ++matched;
  }
  ASSERT_GT(matched, 100);
  KeyFrameInsertion insertion;
  insertion.new_points_min = 100;
  const NewKeyFrame created = insertKeyFrame(*m.map, frame, insertion);
  ASSERT_TRUE(created.kf);
  EXPECT_EQ(m.map->numKeyFrames(), 2u);
  const map::FrameFeatures& f = *frame.features;
  const double close = frame.sensor->closeDepth();
  int observed = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (i % 2 == 0 && first.map_points[i]) {
      EXPECT_EQ(frame.map_points[i], first.map_points[i]);
      observed += first.map_points[i]->isObservedBy(created.kf->id());
    } else if (f.depth[i] > 0 && f.depth[i] < close) {
      ASSERT_TRUE(frame.map_points[i]) << "close keypoint " << i << " got no point";
      EXPECT_LT((frame.map_points[i]->position() - frame.unproject(static_cast<int>(i))).norm(), 1e-9);
    }
  }
  EXPECT_EQ(observed, matched);
  EXPECT_GE(static_cast<int>(created.new_points.size()), 100);
  for (const auto& p : created.new_points) EXPECT_TRUE(p->isObservedBy(created.kf->id()));
}

}  // namespace
}  // namespace amos::tracking
