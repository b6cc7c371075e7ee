#include "amos/dynamic/baseline_tracks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "amos/core/option_error.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/dynamic/box_wall_scene.h"
#include "amos/dynamic/test_scenes.h"
#include "amos/testing/test_camera.h"

namespace amos::dynamic {
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
  const BaselineMotion m = baselineMotion(corners, now.gray, now.depth, poseAt(s.c_now), before.gray,
                                          poseAt(s.c_before), s.camera, s.options.tracking, s.options.reprojection,
                                          s.options.baseline_tracks);
  EXPECT_FALSE(m.ok);
  EXPECT_EQ(m.moving_points, 0);
}

TEST(BaselineTracks, PyramidsBuiltBeforehandGiveTheSameResult) {
  // A pipeline passes the pyramids it built for the corner tracks.
  const Scene s;
  std::vector<cv::Point2f> corners;
  const BaselineMotion from_gray = s.motion(-0.012, 0.0, core::SE3::Identity(), &corners);
  const Frame before = render(s.camera, s.c_before, -0.012), now = render(s.camera, s.c_now, 0.0);
  const BaselineMotion from_pyramids = baselineMotion(
      corners, buildPyramid(now.gray, s.options.tracking), now.depth, poseAt(s.c_now),
      buildPyramid(before.gray, s.options.tracking), poseAt(s.c_before), s.camera, s.options.tracking,
      s.options.reprojection, s.options.baseline_tracks);
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

TEST(BaselineTracks, SparseMovingPointsAreCountedOverTheSurfaceTheySpan) {
  // One moving point on each of superpixels 0-2 (a door leaf with ~1 surviving point per superpixel): none has the
  // two votes of its own, but pooled over its same-surface neighbours they have 2-3.
  const Strip strip;
  BaselineMotion m;
  m.points = {Strip::point(5, true), Strip::point(15, true), Strip::point(25, true), Strip::point(35, true)};
  BaselineTrackOptions o;
  o.pool_neighbours = true;
  o.pooled_votes = 3;
  EXPECT_EQ(baselineMovingSuperpixels(m, strip.labels, 4, o), std::vector<bool>(4, false));  // no graph: alone
  // Superpixel 1 pools 3 (0, 1, 2); 0 pools 2 (0, 1); 2 pools 2 (1, 2: not 3, behind an occlusion edge); 3 pools
  // its own 1.
  EXPECT_EQ(baselineMovingSuperpixels(m, strip.labels, 4, o, &strip.graph),
            (std::vector<bool>{false, true, false, false}));
  o.pooled_votes = 2;
  EXPECT_EQ(baselineMovingSuperpixels(m, strip.labels, 4, o, &strip.graph),
            (std::vector<bool>{true, true, true, false}));
  o.pool_neighbours = false;
  EXPECT_EQ(baselineMovingSuperpixels(m, strip.labels, 4, o, &strip.graph), std::vector<bool>(4, false));
}

TEST(BaselineTracks, ASuperpixelWhosePointsStayIsNotMovedByItsNeighbours) {
  const Strip strip;
  BaselineMotion m;
  m.points = {Strip::point(3, true),  Strip::point(6, true),  Strip::point(9, true),  // 0: three moving
              Strip::point(14, false), Strip::point(16, false),                         // 1: two static ...
              Strip::point(18, true),                                                   // ... one moving
              Strip::point(25, true)};                                                  // 2: one moving
  BaselineTrackOptions o;
  o.pool_neighbours = true;
  o.pooled_votes = 3;
  // 1 pools 5 moving against 2 static but its own points say static; 2 pools 2 moving against 2 static.
  EXPECT_EQ(baselineMovingSuperpixels(m, strip.labels, 4, o, &strip.graph),
            (std::vector<bool>{true, false, false, false}));
}

TEST(BaselineTracks, ASuperpixelIsStaticWhenMostOfItsPointsStayed) {
  const Strip strip;
  BaselineMotion m;
  m.points = {Strip::point(3, true),  Strip::point(6, false), Strip::point(9, false),  // 0: two static, one moving
              Strip::point(14, false), Strip::point(16, true),                         // 1: one each
              Strip::point(25, false), Strip::point(27, false)};                       // 2: two static
  m.points.push_back(Strip::point(35, false));                                         // 3: two static, but one
  m.points.push_back(Strip::point(37, false));                                         //    densified
  m.points.back().densified = true;
  EXPECT_EQ(baselineStaticSuperpixels(m, strip.labels, 4, BaselineTrackOptions{}),
            (std::vector<bool>{true, false, true, false}));
}

TEST(BaselineTracks, WhereAPointMovedMorePointsAreFollowed) {
  // Of the box's corners only one is followed (a door leaf's plain panel: ~1 point per superpixel survives ten
  // frames): its block has one moving vote, not the two it needs. Densifying follows up to four more points in
  // that block and its neighbours: the box's blocks then move on votes of their own, the wall's stay.
  Scene s;
  std::vector<cv::Point2f> corners;
  s.motion(-0.012, 0.0, core::SE3::Identity(), &corners);
  std::vector<cv::Point2f> sparse;
  bool kept_one = false;
  const cv::Point2f centre(320.f, 240.f);
  cv::Point2f kept;
  for (const cv::Point2f& c : corners) {
    if (!onBoxInside(s.camera, s.c_now, 0.0, c)) {
      if (awayFromBox(s.camera, s.c_now, c)) sparse.push_back(c);
    } else if (!kept_one && cv::norm(c - centre) < 20) {
      sparse.push_back(c);
      kept = c;
      kept_one = true;
    }
  }
  ASSERT_TRUE(kept_one);
  const Frame before = render(s.camera, s.c_before, -0.012), now = render(s.camera, s.c_now, 0.0);
  const ImagePyramid pyramid = buildPyramid(now.gray, s.options.tracking),
                     baseline_pyramid = buildPyramid(before.gray, s.options.tracking);
  BaselineMotion m = baselineMotion(sparse, pyramid, now.depth, poseAt(s.c_now), baseline_pyramid,
                                    poseAt(s.c_before), s.camera, s.options.tracking, s.options.reprojection,
                                    s.options.baseline_tracks);
  ASSERT_TRUE(m.ok);
  ASSERT_EQ(m.moving_points, 1);
  int count = 0;
  const cv::Mat labels = blockLabels(s.camera, count);
  SuperpixelGraph graph;
  graph.neighbours = superpixelNeighbours(labels, count);
  for (const auto& n : graph.neighbours) graph.occlusion_edges.emplace_back(n.size(), false);
  // The block of the one moving point (not necessarily the block whose corner is the image centre).
  const int centre_block = labels.at<int>(cvRound(kept.y), cvRound(kept.x)), wall_block = labels.at<int>(40, 40);
  BaselineTrackOptions o = s.options.baseline_tracks;
  EXPECT_FALSE(baselineMovingSuperpixels(m, labels, count, o)[centre_block]);
  // Off (the default): nothing added.
  BaselineMotion unchanged = m;
  EXPECT_EQ(densifyBaselineMotion(unchanged, pyramid, now.depth, poseAt(s.c_now), baseline_pyramid, cv::Mat(),
                                  poseAt(s.c_before), s.camera, labels, count, &graph, s.options.tracking,
                                  s.options.reprojection, o),
            0);
  o.densify_points = 4;
  const std::size_t before_count = m.points.size();
  const int added = densifyBaselineMotion(m, pyramid, now.depth, poseAt(s.c_now), baseline_pyramid, cv::Mat(),
                                          poseAt(s.c_before), s.camera, labels, count, &graph, s.options.tracking,
                                          s.options.reprojection, o);
  EXPECT_GT(added, 12);                        // the block and its eight-ish neighbours, up to four each
  EXPECT_LE(added, 4 * 5);                     // 4-connected: itself and four neighbours
  EXPECT_EQ(m.points.size(), before_count + static_cast<std::size_t>(added));
  const std::vector<bool> moving = baselineMovingSuperpixels(m, labels, count, o);
  EXPECT_TRUE(moving[centre_block]);
  EXPECT_FALSE(moving[wall_block]);
  for (std::size_t i = before_count; i < m.points.size(); ++i) {
    const BaselinePoint& p = m.points[i];
    if (onBoxInside(s.camera, s.c_now, 0.0, p.current)) {
      EXPECT_TRUE(p.moving) << p.current;
    }
    if (awayFromBox(s.camera, s.c_now, p.current)) {
      EXPECT_FALSE(p.moving) << p.current;
    }
  }
  // With the baseline's own depth every densified point was seen there: the same points are followed. Where
  // something stood 30 cm in front of the scene when the baseline was taken, none is (LK would follow the occluder).
  BaselineMotion seen = baselineMotion(sparse, pyramid, now.depth, poseAt(s.c_now), baseline_pyramid,
                                       poseAt(s.c_before), s.camera, s.options.tracking, s.options.reprojection, o);
  BaselineMotion hidden = seen;
  EXPECT_EQ(densifyBaselineMotion(seen, pyramid, now.depth, poseAt(s.c_now), baseline_pyramid, before.depth,
                                  poseAt(s.c_before), s.camera, labels, count, &graph, s.options.tracking,
                                  s.options.reprojection, o),
            added);
  const cv::Mat occluder_depth = before.depth - 0.3;
  EXPECT_EQ(densifyBaselineMotion(hidden, pyramid, now.depth, poseAt(s.c_now), baseline_pyramid, occluder_depth,
                                  poseAt(s.c_before), s.camera, labels, count, &graph, s.options.tracking,
                                  s.options.reprojection, o),
            0);
  // Nothing moved, nothing to densify.
  BaselineMotion still = baselineMotion(sparse, pyramid, now.depth, poseAt(s.c_now), pyramid, poseAt(s.c_now),
                                        s.camera, s.options.tracking, s.options.reprojection, o);
  ASSERT_TRUE(still.ok);
  EXPECT_EQ(densifyBaselineMotion(still, pyramid, now.depth, poseAt(s.c_now), pyramid, cv::Mat(), poseAt(s.c_now),
                                  s.camera, labels, count, &graph, s.options.tracking, s.options.reprojection, o),
            0);
}

TEST(BaselineTracks, OptionsAreChecked) {
  BaselineTrackOptions o;
  o.min_votes = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.cluster_share = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.pooled_votes = 0;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.densify_points = -1;
  EXPECT_THROW(o.check(), core::InvalidOption);
  o = {};
  o.densify_grid_px = 0;
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
}  // namespace amos::dynamic
