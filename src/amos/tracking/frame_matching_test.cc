// Step "match": from the last frame (motion model) or the reference keyframe, a first pose near the truth, with
// matches to the map points that project onto the matched keypoints.
#include "amos/tracking/frame_matching.h"

#include <gtest/gtest.h>

#include <shared_mutex>

#include "amos/map/map_point.h"
#include "amos/testing/pose_matchers.h"
#include "amos/tracking/step_test_scene.h"

namespace amos::tracking {
namespace {

using amos::testing::PoseNear;
using step_test::kDeg;
using step_test::poseAt;

// Each match's map point, projected with the true pose, lands on its keypoint.
int matchesOffTheirKeypoint(const map::Frame& frame, const core::SE3& true_T_cw, double max_px) {
  int off = 0;
  const auto& camera = frame.sensor->camera();
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (!frame.map_points[i]) continue;
    const Eigen::Vector3d pc = true_T_cw * frame.map_points[i]->position();
    const double u = camera.fx() * pc.x() / pc.z() + camera.cx();
    const double v = camera.fy() * pc.y() / pc.z() + camera.cy();
    const cv::Point2f& kp = frame.features->keys[i].pt;
    if (std::hypot(u - kp.x, v - kp.y) > max_px) ++off;
  }
  return off;
}

int countMatches(const map::Frame& frame) {
  int n = 0;
  for (const auto& p : frame.map_points) n += p != nullptr;
  return n;
}

struct TwoFrames {
  step_test::RoomFrames frames;
  map::Frame last = frames.frame(core::SE3::Identity());
  step_test::MapFromFrame mapped = step_test::mapFrom(last, core::SE3::Identity());
  core::SE3 truth = poseAt(0.03, 0.01, 0.02, 0.002, 0.8 * kDeg, 0.001);  // the camera moved 3.7 cm, 0.8 deg
  map::Frame current = frames.frame(truth);
};

// Predicted where the last frame was, 3.7 cm and 0.8 deg off: the projection search finds the last frame's points
// on the keypoints they project to (all but a few within 3 px), and the pose comes within 5 mm and 0.1 deg of the
// truth.
TEST(FrameMatching, TheMotionModelFindsTheLastFramesPointsWhereTheyProject) {
  TwoFrames s;
  std::shared_lock lock(s.mapped.map->mutex());
  const MotionModelMatch m =
      trackWithMotionModel(s.current, s.last, {{core::SE3::Identity(), false}}, TrackerOptions{});
  ASSERT_TRUE(m.tracked);
  EXPECT_FALSE(m.used_external);
  EXPECT_THAT(s.current.T_cw, PoseNear(s.truth, 0.005, 0.1 * kDeg));
  EXPECT_GE(countMatches(s.current), 300);
  EXPECT_LE(matchesOffTheirKeypoint(s.current, s.truth, 3.0), countMatches(s.current) / 20);
}

// The prediction with the most matches wins: an external pose 40 cm off loses to one at the truth, and is reported
// as used when it is the good one.
TEST(FrameMatching, TheMotionModelKeepsThePredictionWithTheMostMatches) {
  TwoFrames s;
  std::shared_lock lock(s.mapped.map->mutex());
  const core::SE3 far = poseAt(-0.4, 0, 0, 0, -5 * kDeg, 0);
  const MotionModelMatch bad_external =
      trackWithMotionModel(s.current, s.last, {{far, true}, {s.truth, false}}, TrackerOptions{});
  EXPECT_TRUE(bad_external.tracked);
  EXPECT_FALSE(bad_external.used_external);
  const MotionModelMatch good_external =
      trackWithMotionModel(s.current, s.last, {{s.truth, true}, {far, false}}, TrackerOptions{});
  EXPECT_TRUE(good_external.tracked);
  EXPECT_TRUE(good_external.used_external);
  EXPECT_THAT(s.current.T_cw, PoseNear(s.truth, 0.005, 0.1 * kDeg));
}

// Descriptor matching to the reference keyframe, the pose optimised from the last one: near the truth.
TEST(FrameMatching, TheReferenceKeyFrameGivesThePose) {
  TwoFrames s;
  std::shared_lock lock(s.mapped.map->mutex());
  ASSERT_TRUE(trackReferenceKeyFrame(s.current, *s.mapped.kf, core::SE3::Identity(), TrackerOptions{}));
  EXPECT_THAT(s.current.T_cw, PoseNear(s.truth, 0.005, 0.1 * kDeg));
  EXPECT_LE(matchesOffTheirKeypoint(s.current, s.truth, 3.0), countMatches(s.current) / 50);
}

// The last frame's unmatched keypoints with depth get temporary points at their depth, closest first: all the
// close ones, at least min_points; matched keypoints keep their map points.
TEST(FrameMatching, TemporaryPointsComeFromTheLastFramesDepthClosestFirst) {
  step_test::RoomFrames frames;
  map::Frame last = frames.frame(core::SE3::Identity());
  last.setPose(core::SE3::Identity());
  const map::FrameFeatures& f = *last.features;
  std::size_t matched = 0;  // a keypoint with depth already matched to a map point
  while (f.depth[matched] <= 0) ++matched;
  const auto kept = std::make_shared<map::MapPoint>(7, Eigen::Vector3d(0, 0, 2), 0, 0);
  kept->addObservation(0, static_cast<int>(matched), true);
  last.map_points[matched] = kept;
  std::vector<map::MapPointPtr> temporaries;
  addTemporaryPoints(last, 100, temporaries);
  const double close = last.sensor->closeDepth();
  int with_depth = 0;
  float farthest = 0;
  for (const auto& p : temporaries) farthest = std::max(farthest, static_cast<float>(p->position().z()));
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] <= 0) {
      EXPECT_FALSE(last.map_points[i]) << "keypoint " << i << " has no depth";
      continue;
    }
    ++with_depth;
    if (i == matched) continue;
    if (f.depth[i] < close || f.depth[i] < farthest) {
      ASSERT_TRUE(last.map_points[i]) << "keypoint " << i << " at " << f.depth[i] << " m";
      EXPECT_LT((last.map_points[i]->position() - last.unproject(static_cast<int>(i))).norm(), 1e-9);
    }
  }
  EXPECT_EQ(last.map_points[matched], kept);
  EXPECT_GE(static_cast<int>(temporaries.size()), std::min(with_depth - 1, 100));
  EXPECT_LE(static_cast<int>(temporaries.size()), with_depth - 1);
}

}  // namespace
}  // namespace amos::tracking
