// Step "predict": the constant-velocity model extrapolates the last motion, the external pose competes with it or
// replaces it, and a recently lost camera is looked for where its last velocity has taken it.
#include "amos/tracking/pose_prediction.h"

#include <gtest/gtest.h>

#include "amos/testing/pose_matchers.h"
#include "amos/testing/synthetic_scene.h"

namespace amos::tracking {
namespace {

using amos::testing::PoseNear;

// A camera moving 2 cm and 0.5 deg per frame, with a little of every other motion.
std::vector<core::SE3> steadyPath(int frames) {
  core::Vector6d xi;
  xi << 0.02, 0.003, -0.004, 0.001, 0.5 * M_PI / 180, 0.0005;
  return testing::constantVelocityPath(frames, xi,
                                       core::makeSE3(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1, -0.2, 0.3)));
}

MotionHistory historyAt(const std::vector<core::SE3>& path, int last) {
  MotionHistory history;
  history.last_T_cw = path[last];
  history.last_tracked = true;
  history.velocity = path[last] * path[last - 1].inverse();
  return history;
}

TEST(PosePrediction, ConstantVelocityGivesTheExtrapolatedPose) {
  const std::vector<core::SE3> path = steadyPath(4);
  const std::vector<PosePrediction> p =
      motionModelPredictions(historyAt(path, 2), std::nullopt, ExternalPosePolicy::kCompete);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_FALSE(p[0].external);
  EXPECT_THAT(p[0].T_cw, PoseNear(path[3], 1e-9, 1e-9));
}

TEST(PosePrediction, TheExternalPoseCompetesFirstOrReplaces) {
  const std::vector<core::SE3> path = steadyPath(4);
  const core::SE3 external = path[0];
  const std::vector<PosePrediction> compete =
      motionModelPredictions(historyAt(path, 2), external, ExternalPosePolicy::kCompete);
  ASSERT_EQ(compete.size(), 2u);
  EXPECT_TRUE(compete[0].external);
  EXPECT_THAT(compete[0].T_cw, PoseNear(external, 1e-12, 1e-12));
  EXPECT_FALSE(compete[1].external);
  EXPECT_THAT(compete[1].T_cw, PoseNear(path[3], 1e-9, 1e-9));
  const std::vector<PosePrediction> replace =
      motionModelPredictions(historyAt(path, 2), external, ExternalPosePolicy::kReplace);
  ASSERT_EQ(replace.size(), 1u);
  EXPECT_TRUE(replace[0].external);
}

// No velocity yet (the frame after a relocalisation): the last tracked pose itself; nothing when it was not tracked.
TEST(PosePrediction, WithoutVelocityTheLastTrackedPose) {
  const std::vector<core::SE3> path = steadyPath(3);
  MotionHistory history = historyAt(path, 2);
  history.velocity.reset();
  const std::vector<PosePrediction> p = motionModelPredictions(history, std::nullopt, ExternalPosePolicy::kCompete);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_THAT(p[0].T_cw, PoseNear(path[2], 1e-12, 1e-12));
  history.last_tracked = false;
  EXPECT_TRUE(motionModelPredictions(history, std::nullopt, ExternalPosePolicy::kCompete).empty());
}

// Tracked up to frame 3, lost since: at frame 9 the camera is looked for at the truth (the velocity carried over six
// frames), then at frame 3's pose; an external pose comes first.
TEST(PosePrediction, RecoveryCarriesTheLastVelocityOverTheGap) {
  const std::vector<core::SE3> path = steadyPath(10);
  LastTrackedPose last;
  last.T_cw = path[3];
  last.frame = 3;
  last.velocity = path[3] * path[2].inverse();
  const std::vector<core::SE3> p = recoveryPredictions(last, 9, std::nullopt);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_THAT(p[0], PoseNear(path[9], 1e-9, 1e-9));
  EXPECT_THAT(p[1], PoseNear(path[3], 1e-12, 1e-12));
  const std::vector<core::SE3> with_external = recoveryPredictions(last, 9, path[0]);
  ASSERT_EQ(with_external.size(), 3u);
  EXPECT_THAT(with_external[0], PoseNear(path[0], 1e-12, 1e-12));
  last.velocity.reset();
  EXPECT_EQ(recoveryPredictions(last, 9, std::nullopt).size(), 1u);
}

}  // namespace
}  // namespace amos::tracking
