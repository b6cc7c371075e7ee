#include "amos/dynamic/corner_tracking.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <string>

#include "amos/core/error.h"
#include "amos/testing/shared_data.h"

namespace amos::dynamic {
namespace {

cv::Mat texture() {
  cv::Mat t(480, 640, CV_8U);
  cv::setRNGSeed(9);
  cv::randu(t, 0, 255);
  cv::GaussianBlur(t, t, cv::Size(0, 0), 2.0);
  return t;
}

TEST(CornerTracking, RecoversAKnownSubpixelShift) {
  const cv::Mat last = texture();
  cv::Mat current;
  const cv::Mat A = (cv::Mat_<double>(2, 3) << 1, 0, 3.5, 0, 1, -2.25);
  cv::warpAffine(last, current, A, last.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const std::vector<PointTrack> tracks = trackCorners(last, current, CornerTrackingOptions{});
  ASSERT_GT(tracks.size(), 300u);
  int close = 0;
  for (const PointTrack& t : tracks) {
    const cv::Point2f d = t.current - t.last;
    if (std::abs(d.x - 3.5f) < 0.1f && std::abs(d.y + 2.25f) < 0.1f) ++close;
  }
  EXPECT_GT(close, static_cast<int>(tracks.size() * 95 / 100));
}

// Corners found ahead (detectCorners on the last frame alone) and tracked later give exactly trackCorners' tracks,
// and a mask keeps them off the masked-out area.
TEST(CornerTracking, CornersDetectedAheadTrackLikeTrackCorners) {
  const cv::Mat last = texture();
  cv::Mat current;
  const cv::Mat A = (cv::Mat_<double>(2, 3) << 1, 0, 1.5, 0, 1, 2.0);
  cv::warpAffine(last, current, A, last.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const CornerTrackingOptions options;
  const std::vector<cv::Point2f> corners = detectCorners(last, options);
  ASSERT_GT(corners.size(), 300u);
  const FramePairPyramids pyramids = buildPyramids(last, current, options);
  const std::vector<PointTrack> ahead = trackPoints(pyramids, corners, options);
  const std::vector<PointTrack> direct = trackCorners(last, pyramids, options);
  ASSERT_EQ(ahead.size(), direct.size());
  for (std::size_t i = 0; i < ahead.size(); ++i) {
    EXPECT_EQ(ahead[i].last, direct[i].last);
    EXPECT_EQ(ahead[i].current, direct[i].current);
  }
  cv::Mat mask(last.size(), CV_8U, cv::Scalar(255));
  mask(cv::Rect(0, 0, 320, 480)).setTo(0);
  const std::vector<cv::Point2f> right = detectCorners(last, options, mask);
  ASSERT_FALSE(right.empty());
  for (const cv::Point2f& c : right) EXPECT_GE(c.x, 319.f);
  EXPECT_THROW(detectCorners(last, options, cv::Mat(10, 10, CV_8U)), core::Error);
}

TEST(CornerTracking, ForwardBackwardCheckDropsOccludedPoints) {
  const cv::Mat last = texture();
  cv::Mat current = last.clone();
  // A new, unrelated texture covers a block of the current frame (an occluder walking in).
  cv::Mat occluder(160, 160, CV_8U);
  cv::randu(occluder, 0, 255);
  cv::GaussianBlur(occluder, occluder, cv::Size(0, 0), 2.0);
  occluder.copyTo(current(cv::Rect(240, 160, 160, 160)));
  std::vector<cv::Point2f> points;
  for (int v = 20; v < 460; v += 20)
    for (int u = 20; u < 620; u += 20) points.emplace_back(u, v);
  const CornerTrackingOptions options;
  const std::vector<PointTrack> tracks = trackPoints(buildPyramids(last, current, options), points, options);
  int inside = 0, total_inside = 0;
  const cv::Rect deep(255, 175, 130, 130);  // the occluder minus half an LK window
  for (const cv::Point2f& p : points) total_inside += deep.contains(p);
  for (const PointTrack& t : tracks) {
    EXPECT_EQ(t.last, points[t.source_index]);
    if (deep.contains(t.last)) ++inside;
    // Far from the occluder (beyond half the coarsest level's window, 15 px * 2^3 / 2) tracks are exact.
    const cv::Rect reach(240 - 90, 160 - 90, 160 + 180, 160 + 180);
    if (!reach.contains(t.last)) {
      EXPECT_LT(cv::norm(t.current - t.last), 0.05);
    }
  }
  EXPECT_GT(total_inside, 30);
  // LK "converges" for every occluded point (both status flags set); the forward-backward check drops most of
  // them. The rest land in local minima consistent in both directions, which no track-only test can tell.
  CornerTrackingOptions no_check = options;
  no_check.forward_backward_px = 1e6;
  int inside_without_check = 0;
  for (const PointTrack& t : trackPoints(buildPyramids(last, current, no_check), points, no_check))
    inside_without_check += deep.contains(t.last);
  EXPECT_EQ(inside_without_check, total_inside);
  // Without the backward pass at all: the same tracks as with an unlimited threshold, end points and order.
  CornerTrackingOptions forward_only = options;
  forward_only.forward_backward_check = false;
  const auto unchecked = trackPoints(buildPyramids(last, current, no_check), points, no_check);
  const auto forward = trackPoints(buildPyramids(last, current, forward_only), points, forward_only);
  ASSERT_EQ(forward.size(), unchecked.size());
  for (std::size_t i = 0; i < forward.size(); ++i) {
    EXPECT_EQ(forward[i].source_index, unchecked[i].source_index);
    EXPECT_EQ(forward[i].current, unchecked[i].current);
  }
  EXPECT_LT(inside, total_inside / 3);
  EXPECT_GT(tracks.size(), points.size() * 3 / 4);
}

// trackPoints sends back only the points whose forward pass succeeded inside the image; LK tracks every point on
// its own, so the result must be exactly that of running both passes on all points (checked on two real frames with
// people walking, where many forward tracks fail or leave the image).
TEST(CornerTracking, BackwardPassOnSurvivorsOnlyChangesNothing) {
  AMOS_REQUIRE_DATA("bonn_crowd_dev");
  const std::string dir = testing::dataPath("bonn_crowd_dev/rgb/");
  const cv::Mat last = cv::imread(dir + "1548339831.57265.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat current = cv::imread(dir + "1548339831.87434.png", cv::IMREAD_GRAYSCALE);  // 9 frames later
  ASSERT_FALSE(last.empty() || current.empty());
  const CornerTrackingOptions options;
  const FramePairPyramids pyramids = buildPyramids(last, current, options);
  std::vector<cv::Point2f> points;
  cv::goodFeaturesToTrack(last, points, 800, 0.005, 5.0);
  points.emplace_back(-3.f, 10.f);  // outside the image
  // Both passes on every point, as plain OpenCV calls.
  const cv::Size window(options.lk_window, options.lk_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, options.lk_max_iterations,
                              options.lk_epsilon);
  std::vector<cv::Point2f> forward, backward;
  std::vector<uchar> ok_forward, ok_backward;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(pyramids.last, pyramids.current, points, forward, ok_forward, error, window,
                           options.lk_levels, stop);
  cv::calcOpticalFlowPyrLK(pyramids.current, pyramids.last, forward, backward, ok_backward, error, window,
                           options.lk_levels, stop);
  std::vector<PointTrack> expected;
  int forward_failures = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool inside = forward[i].x >= 0 && forward[i].y >= 0 && forward[i].x < current.cols - 1 &&
                        forward[i].y < current.rows - 1;
    if (!ok_forward[i] || !inside) {
      ++forward_failures;
      continue;
    }
    const cv::Point2f d = backward[i] - points[i];
    if (ok_backward[i] && d.dot(d) <= options.forward_backward_px * options.forward_backward_px)
      expected.push_back({points[i], forward[i], static_cast<int>(i)});
  }
  EXPECT_GT(forward_failures, 0);
  const std::vector<PointTrack> tracks = trackPoints(pyramids, points, options);
  ASSERT_EQ(tracks.size(), expected.size());
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    EXPECT_EQ(tracks[k].source_index, expected[k].source_index);
    EXPECT_EQ(tracks[k].current, expected[k].current);
  }
}

TEST(CornerTracking, RejectsBadOptionsAndImages) {
  CornerTrackingOptions bad;
  bad.lk_window = 20;
  EXPECT_THROW(bad.check(), core::Error);
  EXPECT_THROW(buildPyramids(cv::Mat(10, 10, CV_8UC3), cv::Mat(10, 10, CV_8UC3), CornerTrackingOptions{}), core::Error);
}

}  // namespace
}  // namespace amos::dynamic
