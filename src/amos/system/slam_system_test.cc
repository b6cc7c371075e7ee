// The whole SLAM system (frame building, tracking, local mapping, loop closing in lock-step) on short synthetic
// sequences with known trajectories: the trajectory it reports is the true one, and a dynamic mask that covers a
// mover keeps the mover out of the map and out of the pose.
#include "amos/system/slam_system.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "amos/testing/pose_matchers.h"
#include "amos/testing/slam_input.h"
#include "amos/testing/synthetic_scene.h"
#include "amos/testing/test_camera.h"

namespace amos::system {
namespace {

using amos::testing::PoseNear;
constexpr double kDeg = M_PI / 180;

SlamOptions testOptions() {
  SlamOptions options;
  options.camera = testing::testIntrinsics();
  options.deterministic = true;
  return options;
}

struct SlamRun {
  std::vector<FrameOutput> frames;
  std::vector<io::StampedPose> trajectory;
  SlamStats stats;
  std::vector<Eigen::Vector3d> points;
};

// Runs every frame of seq; with_mask: each frame's mover mask is its dynamic mask.
SlamRun runSlam(const testing::SyntheticSequence& seq, bool with_mask) {
  SlamSystem slam(testOptions());
  const feature::OrbExtractor orb(slam.options().orb);
  SlamRun run;
  for (int i = 0; i < seq.size(); ++i) {
    const testing::SyntheticView view = seq.view(i);
    const io::RgbdFrame frame = testing::SyntheticSequence::toRgbdFrame(view, i, seq.timestamp(i));
    run.frames.push_back(slam.track(testing::trackInput(orb, frame, with_mask ? view.mover_mask : cv::Mat())));
  }
  slam.finish();
  EXPECT_FALSE(slam.workerFailure());
  run.trajectory = slam.trajectory();
  run.stats = slam.stats();
  run.points = slam.mapPointPositions();
  return run;
}

// Distances of the map points from the static surfaces in pixels of disparity of the virtual stereo pair: at
// depth z one pixel moves a point by z^2 / bf (bf = 40 px m), the resolution of RGB-D tracking's depth (the camera
// stays near the origin here, so z is about the world z). Sorted.
std::vector<double> surfaceErrorsPx(const std::vector<Eigen::Vector3d>& points, const testing::SyntheticScene& scene) {
  std::vector<double> px;
  for (const Eigen::Vector3d& p : points) px.push_back(scene.distanceToStaticSurface(p) / (p.z() * p.z() / 40.0));
  std::sort(px.begin(), px.end());
  return px;
}

double quantile(const std::vector<double>& sorted, double q) {
  return sorted.empty() ? -1.0 : sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
}

// The map points lie on the static surfaces, up to the depth resolution of the virtual stereo pair.
void expectMapOnTheStaticSurfaces(const std::vector<Eigen::Vector3d>& points, const testing::SyntheticScene& scene) {
  const std::vector<double> px = surfaceErrorsPx(points, scene);
  EXPECT_LT(quantile(px, 0.5), 0.25);
  EXPECT_LT(quantile(px, 0.9), 0.75);
  EXPECT_LT(quantile(px, 0.99), 1.5);
}

void expectTrajectoryNear(const SlamRun& run, const testing::SyntheticSequence& seq, double max_m, double max_rad) {
  ASSERT_EQ(run.trajectory.size(), static_cast<std::size_t>(seq.size()));
  for (int i = 0; i < seq.size(); ++i) {
    const io::StampedPose& p = run.trajectory[static_cast<std::size_t>(i)];
    EXPECT_DOUBLE_EQ(p.timestamp, seq.timestamp(i));
    EXPECT_THAT(p.T_wc.inverse(), PoseNear(seq.T_cw(i), max_m, max_rad)) << "frame " << i;
  }
}

// A hand-held sway through the room: +-12 cm and +-3 deg about every axis, one period over the 45 frames.
TEST(SlamSystem, TrajectoryOfASyntheticSequenceIsTheTrueOne) {
  auto room = std::make_shared<const testing::SyntheticScene>(testing::texturedRoom(testing::testIntrinsics()));
  const testing::SyntheticSequence seq(room, testing::swayPath(45, 0.12, 3 * kDeg, 45));
  const SlamRun run = runSlam(seq, false);
  EXPECT_EQ(run.stats.frames, 45u);
  EXPECT_EQ(run.stats.tracked, 45u);
  EXPECT_GE(run.stats.keyframes, 2u);
  EXPECT_GT(run.stats.map_points, 500u);
  expectTrajectoryNear(run, seq, 0.005, 0.2 * kDeg);
  expectMapOnTheStaticSurfaces(run.points, *room);
}

// A large box slides across the view in front of a swaying camera, 2 cm per frame. With its pixels in the dynamic
// mask (the paper's front end, here given the exact mask) no keypoint of it reaches tracking: the camera stays
// at the truth and no map point lies on the box.
TEST(SlamSystem, DynamicMaskKeepsAMoverOutOfTheMapAndThePose) {
  auto scene = std::make_shared<testing::SyntheticScene>(testing::texturedRoom(testing::testIntrinsics()));
  scene->addMovingBox({-0.9, -0.6, 1.8}, {-0.1, 0.4, 2.1},
                      scene->addTexture(testing::noiseTexture(99, cv::Size(160, 200))));
  const testing::SyntheticSequence seq(scene, testing::swayPath(30, 0.02, 0.5 * kDeg, 60), 30,
                                       [](int i) { return std::vector<core::SE3>{testing::translation({0.02 * i, 0, 0})}; });
  const SlamRun masked = runSlam(seq, true);
  EXPECT_EQ(masked.stats.tracked, 30u);
  expectTrajectoryNear(masked, seq, 0.005, 0.2 * kDeg);
  expectMapOnTheStaticSurfaces(masked.points, *scene);
  int removed = 0;
  for (const FrameOutput& f : masked.frames) removed += f.removed_dynamic;
  EXPECT_GT(removed, 30 * 50);
  // Without the mask the box's points enter the map (about one in ten, metres of disparity off the static scene).
  const SlamRun unmasked = runSlam(seq, false);
  EXPECT_GT(quantile(surfaceErrorsPx(unmasked.points, *scene), 0.95), 3.0);
}

}  // namespace
}  // namespace amos::system
