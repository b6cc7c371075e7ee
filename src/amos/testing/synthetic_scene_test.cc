// The test support itself: the synthetic scenes give the answers the other tests rely on (exact depth, the
// movers' pixels, texture ORB can track), and the pose matcher says why it failed.
#include "amos/testing/synthetic_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/feature/orb_extractor.h"
#include "amos/synth/sensor_model.h"
#include "amos/testing/pose_matchers.h"
#include "amos/testing/test_camera.h"

namespace amos::testing {
namespace {

TEST(TestCamera, IsTheCameraOfTheSyntheticSequences) {
  const core::CameraIntrinsics a = testIntrinsics(), b = synth::SensorOptions::tumFr3Intrinsics();
  EXPECT_EQ(a.fx, b.fx);
  EXPECT_EQ(a.fy, b.fy);
  EXPECT_EQ(a.cx, b.cx);
  EXPECT_EQ(a.cy, b.cy);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_NO_THROW(testIntrinsics().check());
  EXPECT_NO_THROW(smallTestIntrinsics().check());
  EXPECT_NO_THROW(bonnIntrinsics().check());
  EXPECT_NO_THROW(tumFr1Intrinsics().check());
}

TEST(TexturedRoom, DepthIsExactAndEveryPixelSeesASurface) {
  const SyntheticScene room = texturedRoom(testIntrinsics());
  const SyntheticView view = room.render(core::SE3::Identity());
  ASSERT_EQ(view.depth.size(), cv::Size(640, 480));
  EXPECT_EQ(cv::countNonZero(view.depth > 0), 640 * 480);  // a closed room
  EXPECT_EQ(cv::countNonZero(view.mover_mask), 0);
  // The optical axis (x = 0) passes between the pillar and the boxes and meets the front wall at z = 4.5 m.
  EXPECT_NEAR(view.depth.at<float>(248, 320), 4.5, 1e-5);
  // Every back-projected pixel lies on a surface of the scene, also from a moved camera.
  core::Vector6d xi;
  xi << 0.1, -0.05, 0.2, 0.02, -0.1, 0.03;
  const core::SE3 T_cw = core::expSE3(xi);
  const SyntheticView moved = room.render(T_cw);
  const core::PinholeCamera cam = testCamera();
  for (int v = 5; v < 480; v += 47)
    for (int u = 3; u < 640; u += 53) {
      const Eigen::Vector3d p_w = T_cw.inverse() * cam.backProject(u, v, moved.depth.at<float>(v, u));
      EXPECT_LT(room.distanceToStaticSurface(p_w), 1e-4) << u << "," << v;
    }
  EXPECT_NEAR(room.distanceToStaticSurface({0, 0, 4.0}), 0.5, 1e-12);
}

TEST(TexturedRoom, OrbFindsFeaturesEverywhere) {
  const SyntheticView view = texturedRoom(testIntrinsics()).render(core::SE3::Identity());
  feature::OrbExtractor orb(feature::OrbOptions{});
  std::vector<cv::KeyPoint> keys;
  cv::Mat descriptors;
  orb.extract(view.gray, keys, descriptors);
  EXPECT_GT(keys.size(), 900u);
  int quadrant[4] = {0, 0, 0, 0};
  for (const cv::KeyPoint& k : keys) ++quadrant[(k.pt.x > 320) + 2 * (k.pt.y > 240)];
  for (int q = 0; q < 4; ++q) EXPECT_GT(quadrant[q], 150) << "quadrant " << q;
}

TEST(CrateScene, MoverMaskIsWhereTheMoverIs) {
  const SyntheticScene scene = crateScene(testIntrinsics());
  ASSERT_EQ(scene.moverCount(), 1);
  const SyntheticView rest = scene.render(core::SE3::Identity());
  // The box face x in [-0.4, 0], y in [-0.2, 0.3] at z = 1.5 m.
  const double u0 = 535.4 * -0.4 / 1.5 + 320.1, u1 = 320.1, v0 = 539.2 * -0.2 / 1.5 + 247.6,
               v1 = 539.2 * 0.3 / 1.5 + 247.6;
  EXPECT_NEAR(cv::countNonZero(rest.mover_mask), (u1 - u0) * (v1 - v0), 0.02 * (u1 - u0) * (v1 - v0));
  EXPECT_EQ(rest.mover_mask.at<uchar>(250, 250), 255);
  EXPECT_EQ(rest.instance.at<std::uint16_t>(250, 250), 1);
  EXPECT_NEAR(rest.depth.at<float>(250, 250), 1.5, 1e-5);
  EXPECT_EQ(rest.mover_mask.at<uchar>(100, 100), 0);
  // Raised 5 cm: its top edge moves up by 539.2 * 0.05 / 1.5 = 18 px.
  const SyntheticView raised = scene.render(core::SE3::Identity(), {translation({0, -0.05, 0})});
  EXPECT_EQ(raised.mover_mask.at<uchar>(static_cast<int>(v0) - 15, 250), 255);
  EXPECT_EQ(rest.mover_mask.at<uchar>(static_cast<int>(v0) - 15, 250), 0);
}

TEST(SyntheticSequence, FramesFollowThePath) {
  auto room = std::make_shared<const SyntheticScene>(texturedRoom(testIntrinsics()));
  core::Vector6d xi;
  xi << 0.01, 0, 0, 0, 0.002, 0;
  const SyntheticSequence seq(room, constantVelocityPath(5, xi), 30);
  ASSERT_EQ(seq.size(), 5);
  EXPECT_THAT(seq.T_cw(0), PoseNear(core::SE3::Identity(), 1e-12, 1e-12));
  EXPECT_NEAR(core::translationNorm(seq.T_cw(4)), 0.04, 1e-3);
  EXPECT_NEAR(core::rotationAngle(seq.T_cw(4)), 0.008, 1e-9);
  EXPECT_NEAR(seq.timestamp(3) - seq.timestamp(0), 0.1, 1e-12);
  const io::RgbdFrame f = seq.rgbdFrame(2);
  EXPECT_EQ(f.index, 2u);
  EXPECT_EQ(f.bgr.type(), CV_8UC3);
  EXPECT_EQ(f.depth.type(), CV_32F);
  const std::vector<core::SE3> sway = swayPath(40, 0.05, 0.05, 40);
  EXPECT_THAT(sway.front(), PoseNear(core::SE3::Identity(), 1e-12, 1e-12));
  EXPECT_THAT(sway.back(), PoseNear(core::SE3::Identity(), 0.02, 0.02));  // nearly one period
}

TEST(PoseNear, MatchesWithinTheBoundsAndExplainsAFailure) {
  core::Vector6d xi;
  xi << 0.003, 0.004, 0, 0, 0, 0.01;  // 5 mm, 0.57 deg
  const core::SE3 truth = core::SE3::Identity(), estimate = core::expSE3(xi) * truth;
  EXPECT_THAT(estimate, PoseNear(truth, 0.006, 0.011));
  EXPECT_THAT(estimate, ::testing::Not(PoseNear(truth, 0.004, 0.011)));  // translation too far
  EXPECT_THAT(estimate, ::testing::Not(PoseNear(truth, 0.006, 0.009)));  // rotation too far
  ::testing::StringMatchResultListener listener;
  EXPECT_FALSE(::testing::ExplainMatchResult(PoseNear(truth, 0.004, 0.011), estimate, &listener));
  EXPECT_NE(listener.str().find("translation error 0.0049"), std::string::npos) << listener.str();
  EXPECT_NE(listener.str().find("m (max 0.004)"), std::string::npos) << listener.str();
  EXPECT_NE(listener.str().find("rotation error 0.57"), std::string::npos) << listener.str();
  const std::string description = ::testing::DescribeMatcher<const core::SE3&>(PoseNear(truth, 0.004, 0.011));
  EXPECT_NE(description.find("within 0.004 m"), std::string::npos) << description;
  EXPECT_EQ(::testing::PrintToString(truth), "t = (0, 0, 0) m, r = (0, 0, 0) rad");
}

}  // namespace
}  // namespace amos::testing
