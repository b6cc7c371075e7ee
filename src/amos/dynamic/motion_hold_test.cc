#include "amos/dynamic/motion_hold.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "amos/core/error.h"
#include "amos/dynamic/test_scenes.h"
#include "amos/testing/test_camera.h"

namespace amos::dynamic {
namespace {

constexpr int kHold = 5;

// A wall 3 m in front of the camera (plane z = 3 in the world), optionally with a plate 1 m in front of it covering
// the pixel rectangle `plate` of the camera at the origin; superpixels are 40 x 40 px blocks (test_scenes.h).
struct Scene {
  core::PinholeCamera camera = testing::testCamera();
  DepthSampleGrid grid{camera, 4};
  int count = 0;
  cv::Mat labels = blockLabels(camera, count);

  cv::Mat wall(const Eigen::Vector3d& centre) const {
    return cv::Mat(camera.height(), camera.width(), CV_32F, cv::Scalar(3.0 - centre.z()));
  }
  // Evidence on the block holding pixel (u, v).
  cv::Mat evidenceAt(int u, int v) const {
    cv::Mat m(camera.height(), camera.width(), CV_8U, cv::Scalar(0));
    m.setTo(255, labels == blockAt(camera, u, v));
    return m;
  }
  cv::Mat noEvidence() const { return cv::Mat(camera.height(), camera.width(), CV_8U, cv::Scalar(0)); }

  // One frame from `centre` after a frame from `last_centre` (whose score and depth are given).
  MotionHold step(const cv::Mat& evidence, const cv::Mat& depth, const Eigen::Vector3d& centre,
                  const cv::Mat& last_score, const cv::Mat& last_depth, const Eigen::Vector3d& last_centre) const {
    MotionHoldInput in;
    in.evidence_mask = &evidence;
    in.labels = &labels;
    in.count = count;
    in.depth = &depth;
    in.T_cw = poseAt(centre);
    in.last_score = &last_score;
    in.last_depth = &last_depth;
    in.T_cw_last = poseAt(last_centre);
    return holdMotion(in, camera, grid, DepthEvidenceOptions{}, kHold);
  }
};

int heldCount(const MotionHold& h) { return h.held_superpixels; }
// The score of the sample nearest pixel (u, v) (samples every 4 px from (2, 2)).
int scoreAt(const MotionHold& h, int u, int v) { return h.score.at<std::uint8_t>(v / 4, u / 4); }

TEST(MotionHold, OneDetectionIsNotCarried) {
  const Scene s;
  const Eigen::Vector3d c(0, 0, 0);
  const cv::Mat depth = s.wall(c), none;
  const MotionHold first = s.step(s.evidenceAt(300, 220), depth, c, none, none, c);
  EXPECT_EQ(heldCount(first), 0);  // found moving: in the mask by its own evidence, not by the hold
  EXPECT_EQ(scoreAt(first, 300, 220), 1);
  EXPECT_EQ(scoreAt(first, 100, 100), 0);
  const MotionHold second = s.step(s.noEvidence(), depth, c, first.score, depth, c);
  EXPECT_EQ(heldCount(second), 0);
  EXPECT_EQ(scoreAt(second, 300, 220), 0);
}

// Found moving in `found` frames in a row, then not: how many frames the hold keeps it (checking that it is the
// right superpixel), up to 50.
int framesHeld(const Scene& s, int found) {
  const Eigen::Vector3d c(0, 0, 0);
  const cv::Mat depth = s.wall(c), none;
  const auto block = static_cast<std::size_t>(blockAt(s.camera, 300, 220));
  MotionHold h = s.step(s.evidenceAt(300, 220), depth, c, none, none, c);
  for (int k = 1; k < found; ++k) h = s.step(s.evidenceAt(300, 220), depth, c, h.score, depth, c);
  int held = 0;
  for (; held < 50; ++held) {
    h = s.step(s.noEvidence(), depth, c, h.score, depth, c);
    if (heldCount(h) == 0) break;
    EXPECT_EQ(heldCount(h), 1);
    EXPECT_TRUE(h.held[block]);
  }
  return held;
}

TEST(MotionHold, ASurfaceIsHeldForAsLongAsItWasSeenMovingUpToTheHold) {
  const Scene s;
  EXPECT_EQ(framesHeld(s, 1), 0);
  EXPECT_EQ(framesHeld(s, 2), 1);
  EXPECT_EQ(framesHeld(s, 3), 2);
  EXPECT_EQ(framesHeld(s, kHold), kHold - 1);
  EXPECT_EQ(framesHeld(s, kHold + 1), kHold);
  EXPECT_EQ(framesHeld(s, 3 * kHold), kHold);  // then it rejoins the static world
}

TEST(MotionHold, TheScoreStaysWithTheSurfaceWhenTheCameraMoves) {
  const Scene s;
  // Sideways by as much as makes the wall 3 m away shift by two blocks (80 px) to the left.
  const Eigen::Vector3d c0(0, 0, 0), c1(80 * 3.0 / s.camera.fx(), 0, 0);
  const cv::Mat d0 = s.wall(c0), d1 = s.wall(c1), none;
  MotionHold h = s.step(s.evidenceAt(300, 220), d0, c0, none, none, c0);
  h = s.step(s.evidenceAt(300, 220), d0, c0, h.score, d0, c0);
  h = s.step(s.noEvidence(), d1, c1, h.score, d0, c0);
  const Eigen::Vector2d moved = s.camera.project(s.camera.backProject(300, 220, 3.0) - c1);
  ASSERT_NEAR(moved.x(), 300 - 80, 1e-6);
  const int now_block = blockAt(s.camera, 220, 220);
  const int old_block = blockAt(s.camera, 300, 220);
  EXPECT_EQ(heldCount(h), 1);
  EXPECT_TRUE(h.held[static_cast<std::size_t>(now_block)]);
  EXPECT_FALSE(h.held[static_cast<std::size_t>(old_block)]);
}

TEST(MotionHold, ASurfaceTheMoverUncoveredDoesNotInheritItsScore) {
  const Scene s;
  const Eigen::Vector3d c(0, 0, 0);
  // The last frame saw a plate 2 m from the camera over the block; this frame sees the wall 3 m away there.
  cv::Mat plate = s.wall(c);
  plate.setTo(2.0, s.labels == blockAt(s.camera, 300, 220));
  const cv::Mat wall = s.wall(c), none;
  MotionHold h = s.step(s.evidenceAt(300, 220), plate, c, none, none, c);
  h = s.step(s.evidenceAt(300, 220), plate, c, h.score, plate, c);
  h = s.step(s.noEvidence(), wall, c, h.score, plate, c);
  EXPECT_EQ(heldCount(h), 0);
  EXPECT_EQ(scoreAt(h, 300, 220), 0);
}

// Held for two frames: the block was seen moving at `before` m (three frames), then it is at `after` m.
int heldAfterDepthChange(const Scene& s, double before, double after) {
  const Eigen::Vector3d c(0, 0, 0);
  const cv::Mat none;
  cv::Mat last = s.wall(c), now = s.wall(c);
  last.setTo(before, s.labels == blockAt(s.camera, 300, 220));
  now.setTo(after, s.labels == blockAt(s.camera, 300, 220));
  MotionHold h = s.step(s.evidenceAt(300, 220), last, c, none, none, c);
  for (int k = 0; k < 2; ++k) h = s.step(s.evidenceAt(300, 220), last, c, h.score, last, c);
  h = s.step(s.noEvidence(), now, c, h.score, last, c);
  return heldCount(h);
}

TEST(MotionHold, OnlyTheSameSurfaceWithinTheSensorsNoiseInheritsTheScore) {
  const Scene s;
  // sigma(2 m) = 6.1 mm: the tolerance is 3 sqrt(2) sigma = 2.6 cm.
  EXPECT_EQ(heldAfterDepthChange(s, 2.0, 2.01), 1);  // a slow mover, 1 cm in a frame
  EXPECT_EQ(heldAfterDepthChange(s, 2.0, 1.98), 1);
  EXPECT_EQ(heldAfterDepthChange(s, 2.0, 2.05), 0);  // what stood 5 cm in front of it left
  EXPECT_EQ(heldAfterDepthChange(s, 2.0, 1.95), 0);
}

TEST(MotionHold, StaticEvidenceEndsTheHold) {
  const Scene s;
  const Eigen::Vector3d c(0, 0, 0);
  const cv::Mat depth = s.wall(c), none;
  const auto block = static_cast<std::size_t>(blockAt(s.camera, 300, 220));
  MotionHold h = s.step(s.evidenceAt(300, 220), depth, c, none, none, c);
  for (int k = 0; k < 3; ++k) h = s.step(s.evidenceAt(300, 220), depth, c, h.score, depth, c);
  // Its points stayed put over the long baseline in this frame: released, and not held in the next one either.
  std::vector<bool> seen_static(static_cast<std::size_t>(s.count), false);
  seen_static[block] = true;
  const cv::Mat evidence = s.noEvidence();
  MotionHoldInput in;
  in.evidence_mask = &evidence;
  in.labels = &s.labels;
  in.count = s.count;
  in.depth = &depth;
  in.T_cw = in.T_cw_last = poseAt(c);
  in.last_score = &h.score;
  in.last_depth = &depth;
  in.seen_static = &seen_static;
  const MotionHold released = holdMotion(in, s.camera, s.grid, DepthEvidenceOptions{}, kHold);
  EXPECT_EQ(heldCount(released), 0);
  EXPECT_EQ(scoreAt(released, 300, 220), 0);
  // Without that evidence it is held.
  EXPECT_EQ(heldCount(s.step(s.noEvidence(), depth, c, h.score, depth, c)), 1);
}

TEST(MotionHold, ASuperpixelIsStillWhenItsTracksMoveWithTheStaticWorldWithinTheNoise) {
  const Scene s;
  auto track = [](float u, float v) { return PointTrack{cv::Point2f(u, v), cv::Point2f(u, v), 0}; };
  const int a = blockAt(s.camera, 100, 100), b = blockAt(s.camera, 300, 220), c = blockAt(s.camera, 500, 400);
  // a: errors 0.1, 0.2, 0.5 px (median 0.2 <= 2 sigma); b: 0.1, 0.6, 0.7 (median 0.6); c: one track only.
  const std::vector<PointTrack> tracks = {track(100, 100), track(105, 100), track(110, 100), track(300, 220),
                                          track(305, 220), track(310, 220), track(500, 400), track(600, 20)};
  const std::vector<std::optional<double>> errors = {0.1, 0.2, 0.5, 0.1, 0.6, 0.7, 0.05, std::nullopt};
  const std::vector<bool> still = stillSuperpixels(tracks, errors, s.labels, s.count, 0.15);
  ASSERT_EQ(still.size(), static_cast<std::size_t>(s.count));
  EXPECT_TRUE(still[static_cast<std::size_t>(a)]);
  EXPECT_FALSE(still[static_cast<std::size_t>(b)]);
  EXPECT_FALSE(still[static_cast<std::size_t>(c)]);
  EXPECT_EQ(std::count(still.begin(), still.end(), true), 1);
}

TEST(MotionHold, WithoutALastFrameNothingIsHeld) {
  const Scene s;
  const Eigen::Vector3d c(0, 0, 0);
  const cv::Mat depth = s.wall(c), none;
  const MotionHold h = s.step(s.noEvidence(), depth, c, none, none, c);
  EXPECT_EQ(heldCount(h), 0);
  EXPECT_EQ(cv::countNonZero(h.score), 0);
}

TEST(MotionHold, BadArgumentsAreRefused) {
  const Scene s;
  const Eigen::Vector3d c(0, 0, 0);
  const cv::Mat depth = s.wall(c), none, evidence = s.noEvidence();
  MotionHoldInput in;
  in.evidence_mask = &evidence;
  in.labels = &s.labels;
  in.count = s.count;
  in.depth = &depth;
  EXPECT_THROW(holdMotion(in, s.camera, s.grid, DepthEvidenceOptions{}, 0), core::Error);
  EXPECT_THROW(holdMotion(in, s.camera, s.grid, DepthEvidenceOptions{}, 255), core::Error);
  const cv::Mat wrong(10, 10, CV_8U, cv::Scalar(0));
  in.last_score = &wrong;
  in.last_depth = &depth;
  EXPECT_THROW(holdMotion(in, s.camera, s.grid, DepthEvidenceOptions{}, kHold), core::Error);
}

}  // namespace
}  // namespace amos::dynamic
