// Step "refine" (features): the local map around a frame's matches, and the pose refined against it from a
// perturbed start; the recovery near a lost camera's predicted pose.
#include "amos/tracking/local_map_refinement.h"

#include <gtest/gtest.h>

#include <shared_mutex>

#include "amos/match/brute_force_search.h"
#include "amos/testing/pose_matchers.h"
#include "amos/tracking/recovery.h"
#include "amos/tracking/step_test_scene.h"

namespace amos::tracking {
namespace {

using amos::testing::PoseNear;
using step_test::kDeg;
using step_test::poseAt;

struct KeyFrameAndFrame {
  step_test::RoomFrames frames;
  map::Frame first = frames.frame(core::SE3::Identity());
  step_test::MapFromFrame mapped = step_test::mapFrom(first, core::SE3::Identity());
  core::SE3 truth = poseAt(0.04, -0.01, 0.03, 0.003, 1.0 * kDeg, -0.002);  // 5 cm and 1 deg from the keyframe
  map::Frame frame = frames.frame(truth);

  // A few of the frame's descriptor matches to the keyframe, as the match step leaves them (at most `keep`).
  void seedMatches(int keep) {
    int n = 0;
    const std::vector<map::MapPointPtr> matches =
        match::matchFrameToKeyFrame(frame, *mapped.kf, 0.7f, match::MatchingOptions{}, &n);
    int kept = 0;
    for (std::size_t i = 0; i < matches.size() && kept < keep; ++i) {
      if (!matches[i]) continue;
      frame.map_points[i] = matches[i];
      ++kept;
    }
  }
};

int matchCount(const map::Frame& frame) {
  int n = 0;
  for (const auto& p : frame.map_points) n += p != nullptr;
  return n;
}

TEST(LocalMap, HoldsTheKeyFramesObservingTheFramesMatchesAndTheirPoints) {
  KeyFrameAndFrame s;
  s.seedMatches(20);
  std::shared_lock lock(s.mapped.map->mutex());
  LocalMap local;
  EXPECT_EQ(local.update(s.frame, *s.mapped.map, 80), s.mapped.kf);
  ASSERT_EQ(local.keyFrames().size(), 1u);
  EXPECT_EQ(local.keyFrames()[0], s.mapped.kf);
  EXPECT_EQ(static_cast<int>(local.points().size()), s.mapped.kf->trackedMapPoints(0));
  map::Frame unmatched = s.frames.frame(s.truth);
  EXPECT_EQ(local.update(unmatched, *s.mapped.map, 80), nullptr);
  EXPECT_TRUE(local.points().empty());
}

// Twenty matches and a start 2 cm and 0.5 deg off the truth: the local map's points are found in the frame (many
// more matches) and the pose comes within 3 mm and 0.1 deg of the truth.
TEST(LocalMapRefinement, RecoversAPerturbedPose) {
  KeyFrameAndFrame s;
  s.seedMatches(20);
  s.frame.setPose(poseAt(0.015, -0.01, 0.008, 0, 0.5 * kDeg, 0) * s.truth);
  std::shared_lock lock(s.mapped.map->mutex());
  LocalMap local;
  const LocalMapSearch search{5, 30};
  const LocalMapRefinement r = refineWithLocalMap(s.frame, local, *s.mapped.map, search, TrackerOptions{});
  EXPECT_TRUE(r.tracked);
  EXPECT_EQ(r.reference, s.mapped.kf);
  EXPECT_GE(r.inliers, 300);
  EXPECT_THAT(s.frame.T_cw, PoseNear(s.truth, 0.003, 0.1 * kDeg));
  LocalMapSearch strict = search;
  strict.min_inliers = 100000;
  s.frame.resetMatches();
  s.seedMatches(20);
  EXPECT_FALSE(refineWithLocalMap(s.frame, local, *s.mapped.map, strict, TrackerOptions{}).tracked);
}

// Inliers count matches to map points not flagged outlier; temporary points (no observation) are not inliers.
TEST(LocalMapRefinement, CountsInliersToMapPointsOnly) {
  KeyFrameAndFrame s;
  s.seedMatches(20);
  std::size_t outlier = 0;
  while (!s.frame.map_points[outlier]) ++outlier;
  s.frame.outlier[outlier] = true;
  std::size_t temporary = 0;
  while (s.frame.map_points[temporary]) ++temporary;
  s.frame.map_points[temporary] =
      std::make_shared<map::MapPoint>(map::kNoMapPoint, Eigen::Vector3d(0, 0, 2), map::kNoKeyFrame, s.frame.id);
  EXPECT_EQ(countFoundInliers(s.frame), matchCount(s.frame) - 2);
}

// A lost frame (no matches) whose first prediction is turned 15 deg away and second 1 cm off: the wide search around
// the second and PnP find the pose.
TEST(Recovery, FindsTheFrameNearTheRightPrediction) {
  KeyFrameAndFrame s;
  s.seedMatches(20);
  std::shared_lock lock(s.mapped.map->mutex());
  LocalMap local;
  local.update(s.frame, *s.mapped.map, 80);
  map::Frame lost = s.frames.frame(s.truth);
  const std::vector<core::SE3> predictions{poseAt(0, 0, 0, 0, 15 * kDeg, 0) * s.truth,
                                           poseAt(0.01, 0, 0, 0, 0.3 * kDeg, 0) * s.truth};
  ASSERT_TRUE(recoverNearPredictions(lost, predictions, local, TrackerOptions{}));
  EXPECT_THAT(lost.T_cw, PoseNear(s.truth, 0.005, 0.1 * kDeg));
  map::Frame hopeless = s.frames.frame(s.truth);
  EXPECT_FALSE(recoverNearPredictions(hopeless, {predictions[0]}, local, TrackerOptions{}));
  EXPECT_EQ(matchCount(hopeless), 0);
}

}  // namespace
}  // namespace amos::tracking
