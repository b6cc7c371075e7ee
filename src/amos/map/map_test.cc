#include "amos/map/map.h"

#include <gtest/gtest.h>

#include <random>
#include "amos/testing/test_camera.h"

namespace amos::map {
namespace {

std::shared_ptr<const Sensor> testSensor() {
  return std::make_shared<Sensor>(testing::testIntrinsics(), SensorOptions{}, feature::OrbOptions{});
}

// A frame with n keypoints on a grid, all with depth 2 m, random descriptors, at pose T_cw.
Frame syntheticFrame(FrameId id, int n, const core::SE3& T_cw, unsigned seed) {
  auto sensor = testSensor();
  auto f = std::make_shared<FrameFeatures>();
  std::mt19937 rng(seed);
  f->descriptors.create(n, 32, CV_8U);
  cv::randu(f->descriptors, 0, 256);
  for (int i = 0; i < n; ++i) {
    f->keys.emplace_back(cv::Point2f(20.0f + 10.0f * (i % 60), 20.0f + 10.0f * (i / 60)), 7.0f, 0.0f, 0.0f, 0);
    f->depth.push_back(2.0f);
    f->u_right.push_back(f->keys.back().pt.x - static_cast<float>(sensor->bf() / 2.0));
  }
  f->grid = feature::KeypointGrid(cv::Rect2d(0, 0, 640, 480), f->keys);
  Frame frame = makeFrame(id, static_cast<double>(id), sensor, f, cv::Mat(), cv::Mat());
  frame.setPose(T_cw);
  return frame;
}

core::SE3 shifted(double x) {
  core::SE3 T = core::SE3::Identity();
  T.translation() = Eigen::Vector3d(-x, 0, 0);
  return T;
}

struct ThreeKeyFrames {
  Map map;
  std::vector<KeyFramePtr> kfs;
  std::vector<MapPointPtr> points;
};

// kf0 creates 40 points; kf1 sees the first 30, kf2 the first 20 (so kf1-kf2 share 20, kf0-kf2 20, kf0-kf1 30).
void build(ThreeKeyFrames& s) {
  for (int k = 0; k < 3; ++k) {
    Frame f = syntheticFrame(k, 40, shifted(0.1 * k), 10 + k);
    auto kf = std::make_shared<KeyFrame>(s.map.newKeyFrameId(), f);
    s.map.addKeyFrame(kf);
    s.kfs.push_back(kf);
  }
  for (int i = 0; i < 40; ++i) {
    s.points.push_back(s.map.createMapPoint(Eigen::Vector3d(0.01 * i, 0, 2), s.kfs[0], i, 0));
  }
  for (int i = 0; i < 30; ++i) s.map.addObservation(s.points[i], s.kfs[1], i);
  for (int i = 0; i < 20; ++i) s.map.addObservation(s.points[i], s.kfs[2], i);
  for (const auto& kf : s.kfs) s.map.updateConnections(kf);
}

TEST(Map, ObservationsAreKeptOnBothSides) {
  ThreeKeyFrames s;
  build(s);
  EXPECT_EQ(s.map.numMapPoints(), 40u);
  EXPECT_EQ(s.points[0]->observations().size(), 3u);
  EXPECT_EQ(s.points[0]->numObservations(), 6);  // with depth: counted twice
  EXPECT_EQ(s.kfs[1]->mapPoint(5), s.points[5]);
  EXPECT_EQ(s.points[35]->observations().size(), 1u);
  EXPECT_EQ(s.kfs[0]->trackedMapPoints(0), 40);
  EXPECT_EQ(s.kfs[0]->trackedMapPoints(4), 30);
}

TEST(Map, CovisibilityWeightsAndSpanningTree) {
  ThreeKeyFrames s;
  build(s);
  EXPECT_EQ(s.kfs[0]->weight(s.kfs[1]->id()), 30);
  EXPECT_EQ(s.kfs[0]->weight(s.kfs[2]->id()), 20);
  EXPECT_EQ(s.kfs[2]->weight(s.kfs[1]->id()), 20);
  EXPECT_EQ(s.kfs[0]->orderedConnections().front().second, s.kfs[1]->id());
  EXPECT_EQ(s.kfs[1]->parent(), s.kfs[0]->id());
  EXPECT_EQ(s.kfs[2]->parent(), s.kfs[0]->id());  // tie 20/20 -> lower id
  EXPECT_EQ(s.kfs[0]->parent(), kNoKeyFrame);     // the first keyframe is the root
  EXPECT_EQ(s.kfs[1]->bestCovisibles(1), std::vector<KeyFrameId>{s.kfs[0]->id()});
}

TEST(Map, WeakLinksBelowThresholdKeepOnlyTheBest) {
  Map map(CovisibilityOptions{25});
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 3; ++k) {
    auto kf = std::make_shared<KeyFrame>(map.newKeyFrameId(), syntheticFrame(k, 40, shifted(0.1 * k), k));
    map.addKeyFrame(kf);
    kfs.push_back(kf);
  }
  for (int i = 0; i < 20; ++i) {
    auto p = map.createMapPoint(Eigen::Vector3d(0.01 * i, 0, 2), kfs[2], i, 2);
    if (i < 10) map.addObservation(p, kfs[0], i);
    map.addObservation(p, kfs[1], i);
  }
  map.updateConnections(kfs[2]);
  EXPECT_EQ(kfs[2]->connectionWeights().size(), 1u);  // 20 and 10 < 25: the best (kf1, 20) is kept
  EXPECT_EQ(kfs[2]->weight(kfs[1]->id()), 20);
}

TEST(Map, ReplaceMovesObservationsAndCounters) {
  ThreeKeyFrames s;
  build(s);
  // Point 35 (kf0 only) and point 25 (kf0, kf1): fuse 35 into 25 as if they were duplicates.
  s.points[35]->increaseFound(5);
  const int found_before = s.points[25]->found();
  s.map.replaceMapPoint(s.points[35], s.points[25]);
  EXPECT_TRUE(s.points[35]->isBad());
  EXPECT_EQ(s.points[35]->replacedBy(), s.points[25]);
  EXPECT_EQ(s.map.mapPoint(s.points[35]->id()), nullptr);
  EXPECT_EQ(s.kfs[0]->mapPoint(35), nullptr);  // kf0 already saw point 25 at index 25
  EXPECT_EQ(s.points[25]->found(), found_before + 6);
}

TEST(Map, PointWithTooFewObservationsBecomesBad) {
  ThreeKeyFrames s;
  build(s);
  auto p = s.points[25];  // kf0 + kf1, 4 counted observations
  s.map.eraseObservation(p, s.kfs[1]->id());
  EXPECT_TRUE(p->isBad());
  EXPECT_EQ(s.kfs[0]->mapPoint(25), nullptr);
  EXPECT_EQ(s.map.numMapPoints(), 39u);
}

TEST(Map, RemovedKeyFrameFollowsItsParent) {
  ThreeKeyFrames s;
  build(s);
  const core::SE3 before = s.kfs[2]->T_cw();
  s.map.setKeyFrameBad(s.kfs[2]);
  EXPECT_TRUE(s.kfs[2]->isBad());
  EXPECT_EQ(s.map.numKeyFrames(), 2u);
  EXPECT_EQ(s.kfs[0]->weight(s.kfs[2]->id()), 0);
  EXPECT_EQ(s.points[0]->observations().size(), 2u);
  EXPECT_TRUE(s.map.keyFramePose(s.kfs[2]->id()).isApprox(before));
  // Moving the parent (as bundle adjustment would) moves the removed keyframe with it: kf0 was at identity when
  // kf2 was removed, so kf2's pose relative to it is `before`.
  core::SE3 moved = s.kfs[0]->T_cw();
  moved.translation() += Eigen::Vector3d(0, 0.5, 0);
  s.kfs[0]->setPose(moved);
  EXPECT_TRUE(s.map.keyFramePose(s.kfs[2]->id()).isApprox(before * moved, 1e-12));
  // The first keyframe is never removed.
  s.map.setKeyFrameBad(s.kfs[0]);
  EXPECT_FALSE(s.kfs[0]->isBad());
}

// Tracking inserts keyframes while mapping works on older ones: kf1 gets its first connections only after kf2 exists
// and shares more points with kf2 than with kf0. Its parent must still be the older kf0; with kf2 as parent (kf2's
// parent being kf1) removing both left a parent chain that never reached a live keyframe, and writing the
// trajectory failed at the end of a long run.
TEST(Map, ParentsAreOlderSoRemovedChainsEnd) {
  Map map;
  std::vector<KeyFramePtr> kfs;
  for (int k = 0; k < 4; ++k) {
    Frame f = syntheticFrame(k, 60, shifted(0.1 * k), 20 + k);
    kfs.push_back(std::make_shared<KeyFrame>(map.newKeyFrameId(), f));
    map.addKeyFrame(kfs.back());
  }
  std::vector<MapPointPtr> points;
  for (int i = 0; i < 20; ++i) {  // 20 points of kf0, seen by kf1 and kf3
    points.push_back(map.createMapPoint(Eigen::Vector3d(0.01 * i, 0, 2), kfs[0], i, 0));
    map.addObservation(points.back(), kfs[1], i);
    map.addObservation(points.back(), kfs[3], i);
  }
  for (int i = 20; i < 60; ++i) {  // 40 points of kf1, seen by kf2
    points.push_back(map.createMapPoint(Eigen::Vector3d(0.01 * i, 0.1, 2), kfs[1], i, 1));
    map.addObservation(points.back(), kfs[2], i);
  }
  map.updateConnections(kfs[0]);
  map.updateConnections(kfs[2]);  // kf2 first: its best covisible is kf1 (40), older -> parent kf1
  map.updateConnections(kfs[1]);  // kf1's best covisible is kf2 (40 > 20), but kf2 is newer -> parent kf0
  map.updateConnections(kfs[3]);
  EXPECT_EQ(kfs[2]->parent(), kfs[1]->id());
  EXPECT_EQ(kfs[1]->parent(), kfs[0]->id());
  const core::SE3 pose1 = kfs[1]->T_cw(), pose2 = kfs[2]->T_cw();
  map.setKeyFrameBad(kfs[1]);
  map.setKeyFrameBad(kfs[2]);
  EXPECT_TRUE(map.keyFramePose(kfs[1]->id()).isApprox(pose1, 1e-12));
  EXPECT_TRUE(map.keyFramePose(kfs[2]->id()).isApprox(pose2, 1e-12));
}

TEST(Map, DynamicPointCandidates) {
  ThreeKeyFrames s;
  build(s);
  s.points[3]->increaseMaskedViews(10);
  s.points[3]->increaseDynamicHits(8);
  s.points[4]->increaseMaskedViews(10);
  s.points[4]->increaseDynamicHits(2);
  const auto ids = s.map.dynamicPointCandidates(3, 0.5);
  ASSERT_EQ(ids.size(), 1u);
  EXPECT_EQ(ids[0], s.points[3]->id());
}

}  // namespace
}  // namespace amos::map
