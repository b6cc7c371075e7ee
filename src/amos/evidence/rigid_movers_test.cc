#include "amos/evidence/rigid_movers.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "amos/core/option_error.h"
#include "amos/evidence/box_wall_scene.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/dynamic/test_scenes.h"

namespace amos::evidence {

using namespace dynamic;  // NOLINT(google-build-using-namespace): the front end's types
namespace {
using box_wall::Frame;
using box_wall::render;
using box_wall::Scene;

// The box of box_wall_scene.h (0.6 m at 1.5 m, centred in the view) covers u in [213, 427], v in [133, 347] of the
// current frame; the blocks wholly inside it, and the wall's blocks at least a block away from it.
bool blockInsideBox(int col, int row) { return col >= 6 && col <= 9 && row >= 4 && row <= 7; }
bool blockAwayFromBox(int col, int row) { return col <= 3 || col >= 12 || row <= 1 || row >= 10; }

struct Judged {
  BaselineMotion motion;
  RigidMoverVerdict verdict;
  int count = 0;
  cv::Mat labels;
};

// keep_every > 1 keeps one point in so many, as sparse as the corners on a door leaf (about one per superpixel).
Judged judge(const Scene& s, double box_before, double box_now, const RigidMoverOptions& options, int keep_every = 1) {
  Judged j;
  j.motion = s.motion(box_before, box_now);
  std::vector<BaselinePoint> kept;
  for (std::size_t i = 0; i < j.motion.points.size(); i += keep_every) kept.push_back(j.motion.points[i]);
  j.motion.points = kept;
  j.motion.moving_points = static_cast<int>(std::count_if(kept.begin(), kept.end(), [](const BaselinePoint& p) { return p.moving; }));
  const Frame before = render(s.camera, s.c_before, box_before), now = render(s.camera, s.c_now, box_now);
  j.labels = blockLabels(s.camera, j.count);
  const core::SE3 T_cw_now = poseAt(s.c_now), T_cw_before = poseAt(s.c_before);
  const RigidMoverFrames frames{s.camera, {now.gray, now.depth, T_cw_now}, {before.gray, before.depth, T_cw_before}};
  j.verdict = rigidMoverSuperpixels(j.motion, frames, {j.labels, j.count}, s.options.reprojection, options);
  return j;
}

TEST(RigidMovers, ASlowBoxIsFoundWholeByItsRigidMotion) {
  // 1.2 cm in 10 frames at 1.5 m: 4.3 px over the baseline, 0.4 px per frame.
  const Scene s;
  const Judged j = judge(s, -0.012, 0.0, RigidMoverOptions{}, 8);
  ASSERT_GE(j.motion.moving_points, 8);
  ASSERT_EQ(j.verdict.movers.size(), 1u);
  EXPECT_NEAR(j.verdict.movers[0].shift_px, 535.0 * 0.012 / 1.5, 0.5);
  // The mover's motion: the camera's (4 cm left, 2 cm back) and the box's 1.2 cm to the right, at the box's depth.
  const Eigen::Vector3d on_box(0.0, 0.0, 1.5);
  const Eigen::Vector3d expected = j.verdict.T_bc_static * (on_box - Eigen::Vector3d(0.012, 0.0, 0.0));
  EXPECT_LT((j.verdict.movers[0].T_bc * on_box - expected).norm(), 0.004);
  const int cols = (s.camera.width() + kTestBlock - 1) / kTestBlock;
  int inside = 0, inside_moving = 0;
  for (int b = 0; b < j.count; ++b) {
    const int col = b % cols, row = b / cols;
    if (blockInsideBox(col, row)) ++inside, inside_moving += j.verdict.moving[b];
    if (blockAwayFromBox(col, row)) {
      EXPECT_FALSE(j.verdict.moving[b]) << "wall block " << col << "," << row;
    }
  }
  EXPECT_EQ(inside, 16);
  EXPECT_EQ(inside_moving, inside);
  // Where the sparse points' own vote (two moving points per superpixel) finds only some of them.
  const std::vector<bool> by_points = baselineMovingSuperpixels(j.motion, j.labels, j.count, s.options.baseline_tracks);
  int inside_by_points = 0;
  for (int b = 0; b < j.count; ++b) inside_by_points += by_points[b] && blockInsideBox(b % cols, b / cols);
  EXPECT_LT(inside_by_points, inside / 2);
}

TEST(RigidMovers, TheSuperpixelsNearAMoverAreThoseWithinReachOfItsPointsBox) {
  RigidMover mover;
  mover.region = cv::Rect2f(100.f, 100.f, 50.f, 40.f);  // u in [100, 150], v in [100, 140]
  std::vector<Superpixel> superpixels(5);
  const float centres[5][2] = {{120, 120}, {75, 120}, {69, 120}, {120, 171}, {190, 190}};
  for (int s = 0; s < 5; ++s) superpixels[s].x = centres[s][0], superpixels[s].y = centres[s][1];
  EXPECT_EQ(superpixelsNearMovers(superpixels, {mover}, 30), (std::vector<bool>{true, true, false, false, false}));
  RigidMover second;
  second.region = cv::Rect2f(180.f, 180.f, 20.f, 20.f);
  EXPECT_EQ(superpixelsNearMovers(superpixels, {mover, second}, 30),
            (std::vector<bool>{true, true, false, false, true}));
  EXPECT_EQ(superpixelsNearMovers(superpixels, {}, 30), std::vector<bool>(5, false));
}

TEST(RigidMovers, AStaticSceneHasNoMover) {
  const Scene s;
  const Judged j = judge(s, 0.0, 0.0, RigidMoverOptions{});
  EXPECT_TRUE(j.verdict.movers.empty());
  EXPECT_EQ(j.verdict.moving_superpixels, 0);
  EXPECT_EQ(std::count(j.verdict.moving.begin(), j.verdict.moving.end(), true), 0);
}

TEST(RigidMovers, TooFewMovingPointsMakeNoMover) {
  const Scene s;
  RigidMoverOptions options;
  options.min_inliers = 1000;  // more than the box holds
  const Judged j = judge(s, -0.012, 0.0, options);
  EXPECT_TRUE(j.verdict.movers.empty());
  EXPECT_EQ(j.verdict.moving_superpixels, 0);
}

TEST(RigidMovers, OptionsAreChecked) {
  RigidMoverOptions o;
  o.min_inliers = 5;  // fewer than fix a rigid motion with any to spare
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = RigidMoverOptions{};
  o.inlier_px = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = RigidMoverOptions{};
  o.min_samples = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
}

}  // namespace
}  // namespace amos::evidence
