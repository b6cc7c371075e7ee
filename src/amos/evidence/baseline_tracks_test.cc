#include "amos/evidence/baseline_tracks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "amos/core/option_error.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/evidence/box_wall_scene.h"
#include "amos/dynamic/test_scenes.h"
#include "amos/testing/test_camera.h"

namespace amos::evidence {

using namespace dynamic;  // NOLINT(google-build-using-namespace): the front end's types
namespace {
using box_wall::awayFromBox;
using box_wall::Frame;
using box_wall::onBoxInside;
using box_wall::render;
using box_wall::Scene;

TEST(BaselineTracks, StaticSceneSeenFromAMovingCameraDoesNotMove) {
  const Scene s;
  const BaselineMotion m = s.motion(0.0, 0.0);
  ASSERT_TRUE(m.ok);
  EXPECT_GT(m.points.size(), 200u);
  EXPECT_LT(m.shift_px.norm(), 0.1);
  // Away from the box's edges every point stays within LK's noise; next to them (the coarse pyramid levels see the
  // occlusion edge) one may slip, but never two in one superpixel.
  for (const BaselinePoint& p : m.points) {
    if (awayFromBox(s.camera, s.c_now, p.current)) {
      EXPECT_LT(p.residual_px, 0.5) << p.current;
    }
  }
  EXPECT_LE(m.moving_points, 2);
  int count = 0;
  const cv::Mat labels = blockLabels(s.camera, count);
  const std::vector<bool> moving = baselineMovingSuperpixels(m, labels, count, s.options.baseline_tracks);
  EXPECT_EQ(std::count(moving.begin(), moving.end(), true), 0);
}

TEST(BaselineTracks, ABoxTooSlowForOneFrameMovesOverTheBaseline) {
  // 1.2 cm in 10 frames at 1.5 m: 0.4 px per frame (inside the one-frame bar of 1 px), 4.3 px over the baseline.
  const Scene s;
  const BaselineMotion m = s.motion(-0.012, 0.0);
  ASSERT_TRUE(m.ok);
  EXPECT_DOUBLE_EQ(m.bar_px, 2.0);  // clean images: the floor
  int on_box = 0, on_box_moving = 0, off_box_moving = 0;
  for (const BaselinePoint& p : m.points) {
    if (onBoxInside(s.camera, s.c_now, 0.0, p.current)) {
      ++on_box;
      on_box_moving += p.moving;
      EXPECT_NEAR(p.residual_px, 535.0 * 0.012 / 1.5, 0.5) << p.current;
    } else if (awayFromBox(s.camera, s.c_now, p.current)) {
      off_box_moving += p.moving;  // the wall, away from where the box's edges hid or revealed it
    }
  }
  EXPECT_GT(on_box, 20);
  EXPECT_EQ(on_box_moving, on_box);
  EXPECT_EQ(off_box_moving, 0);

  int count = 0;
  const cv::Mat labels = blockLabels(s.camera, count);
  const std::vector<bool> moving = baselineMovingSuperpixels(m, labels, count, s.options.baseline_tracks);
  const std::vector<bool> clusters = baselineMovingClusters(m, labels, count, s.options.baseline_tracks);
  EXPECT_EQ(moving, clusters);  // blocks as clusters: with the same points, a majority passes the half share
  const int box_block = labels.at<int>(240, 320), wall_block = labels.at<int>(40, 40);
  EXPECT_TRUE(moving[box_block]);
  EXPECT_FALSE(moving[wall_block]);
}

TEST(BaselineTracks, TheCommonShiftOfAPoseErrorIsNotMotion) {
  // 0.3 deg of yaw and 5 mm: ~3-4 px everywhere, which the static points alone would call motion.
  const Scene s;
  core::SE3 error = core::SE3::Identity();
  error.linear() = Eigen::AngleAxisd(0.3 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  error.translation() = Eigen::Vector3d(0.005, 0, 0);
  const BaselineMotion still = s.motion(0.0, 0.0, error);
  ASSERT_TRUE(still.ok);
  EXPECT_GT(still.shift_px.norm(), 2.5);
  EXPECT_LE(still.moving_points, 2);
  const BaselineMotion slow = s.motion(-0.012, 0.0, error);
  EXPECT_GT(slow.moving_points, 60);
}

TEST(BaselineTracks, WithoutEnoughPointsNothingMoves) {
  Scene s;
  std::vector<cv::Point2f> corners;
  s.motion(-0.012, 0.0, core::SE3::Identity(), &corners);
  corners.resize(10);  // below Dynamic.Reprojection.refitMinPoints (30)
  const Frame before = render(s.camera, s.c_before, -0.012), now = render(s.camera, s.c_now, 0.0);
  const core::SE3 T_cw_now = poseAt(s.c_now), T_cw_before = poseAt(s.c_before);
  const BaselineMotion m =
      baselineMotion(corners, BaselineImages{now.gray, now.depth, T_cw_now, before.gray, T_cw_before}, s.camera,
                     s.options);
  EXPECT_FALSE(m.ok);
  EXPECT_EQ(m.moving_points, 0);
}

TEST(BaselineTracks, PyramidsBuiltBeforehandGiveTheSameResult) {
  // A pipeline passes the pyramids it built for the corner tracks.
  const Scene s;
  std::vector<cv::Point2f> corners;
  const BaselineMotion from_gray = s.motion(-0.012, 0.0, core::SE3::Identity(), &corners);
  const Frame before = render(s.camera, s.c_before, -0.012), now = render(s.camera, s.c_now, 0.0);
  const ImagePyramid pyramid = buildPyramid(now.gray, s.options.tracking);
  const ImagePyramid baseline_pyramid = buildPyramid(before.gray, s.options.tracking);
  const core::SE3 T_cw_now = poseAt(s.c_now), T_cw_before = poseAt(s.c_before);
  const BaselineMotion from_pyramids = baselineMotion(
      corners, BaselinePyramids{pyramid, now.depth, T_cw_now, baseline_pyramid, T_cw_before}, s.camera, s.options);
  ASSERT_EQ(from_gray.points.size(), from_pyramids.points.size());
  EXPECT_EQ(from_gray.moving_points, from_pyramids.moving_points);
  for (std::size_t i = 0; i < from_gray.points.size(); ++i)
    EXPECT_EQ(from_gray.points[i].found, from_pyramids.points[i].found) << i;
}

// A row of four superpixels (10 px wide, labels 0-3), neighbours in a chain; the border between 2 and 3 is an
// occlusion edge.
struct Strip {
  cv::Mat labels = cv::Mat(10, 40, CV_32S);
  SuperpixelGraph graph;
  Strip() {
    for (int x = 0; x < 40; ++x) labels.col(x).setTo(x / 10);
    graph.neighbours = {{1}, {0, 2}, {1, 3}, {2}};
    graph.occlusion_edges = {{false}, {false, false}, {false, true}, {true}};
  }
  static BaselinePoint point(float x, bool moving) {
    BaselinePoint p;
    p.current = cv::Point2f(x, 5.f);
    p.moving = moving;
    return p;
  }
};

TEST(BaselineTracks, OptionsAreChecked) {
  BaselineTrackOptions o;
  o.min_votes = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.cluster_share = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.grow_dissimilarity = -1;
  EXPECT_THROW(o.check(), core::InvalidOption);
  DynamicOptions d;
  d.baseline_tracks.enabled = true;
  d.depth.baseline_frames = 1;
  EXPECT_THROW(d.check(), core::InvalidOption);
  d.depth.baseline_frames = 10;
  EXPECT_NO_THROW(d.check());
}

}  // namespace
}  // namespace amos::evidence
