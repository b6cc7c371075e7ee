#include "amos/dynamic/candidate_scoring.h"

#include <gtest/gtest.h>

#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

// The small test camera looking at a wall 2 m away, with the same pose in both frames; the decision map splits the
// frame into cluster 0 (x < 60) and cluster 1.
FrontEndInput wallFrame() { return wallFramePair({120, 100}, 2.f); }

cv::Mat leftRightClusters() {
  cv::Mat map(100, 120, CV_32S, cv::Scalar(0));
  map(cv::Rect(60, 0, 60, 100)).setTo(1);
  return map;
}

// 15 still tracks in cluster 0, then 15 in cluster 1 that moved 5 px to the right.
std::vector<PointTrack> stillLeftMovingRight() {
  std::vector<PointTrack> tracks;
  for (float dx : {0.f, 60.f})
    for (float y : {20.f, 40.f, 60.f})
      for (float x : {10.f, 20.f, 30.f, 40.f, 50.f})
        tracks.push_back({{x + dx, y}, {x + dx + (dx > 0 ? 5.f : 0.f), y}});
  return tracks;
}

TEST(CandidateScoring, TheMovingClusterIsACandidateAndItsTracksStayOutOfTheFits) {
  const std::vector<PointTrack> tracks = stillLeftMovingRight();
  FrontEndInput in = wallFrame();
  in.last_mask = cv::Mat(100, 120, CV_8U, cv::Scalar(0));
  in.last_mask.at<uchar>(20, 20) = 255;  // track 1 started on the last frame's mover
  PriorRegions prior;
  prior.count = 1;
  prior.components = cv::Mat(100, 120, CV_32S, cv::Scalar(0));
  prior.components(cv::Rect(5, 15, 10, 10)).setTo(1);  // track 0 ends in a prior region
  const cv::Mat clusters = leftRightClusters();
  DynamicDiagnostics diag;
  const CandidateScoring scoring =
      scoreCandidates(tracks, in, {clusters, 2, prior}, smallTestCamera(), DynamicOptions{}, diag);
  EXPECT_EQ(diag.tracks_with_depth, 30);
  ASSERT_EQ(scoring.cluster_scores.size(), 2u);
  EXPECT_FALSE(scoring.cluster_scores[0].candidate);
  EXPECT_TRUE(scoring.cluster_scores[1].candidate);
  EXPECT_NEAR(scoring.cluster_scores[1].equivalent_px, 5.0, 1e-6);
  for (int i = 0; i < 30; ++i) {
    EXPECT_EQ(scoring.cluster_of_track[i], i < 15 ? 0 : 1) << i;
    ASSERT_TRUE(scoring.errors_px[i]) << i;
    EXPECT_NEAR(*scoring.errors_px[i], i < 15 ? 0.0 : 5.0, 1e-6) << i;
    // Outside now: cluster 0 but the prior region's track; for the fits also without the last mask's track.
    EXPECT_EQ(scoring.outside_now[i], i < 15 && i != 0) << i;
    EXPECT_EQ(scoring.outside_candidates[i], i < 15 && i != 0 && i != 1) << i;
  }
  // Without the temporal exclusion the last mask changes nothing.
  DynamicOptions no_temporal;
  no_temporal.temporal.exclude_last_mask_from_fits = false;
  const CandidateScoring plain =
      scoreCandidates(tracks, in, {clusters, 2, prior}, smallTestCamera(), no_temporal, diag);
  EXPECT_EQ(plain.outside_candidates, plain.outside_now);
}

TEST(CandidateScoring, TracksOnADepthEdgeGetAnIntervalInsteadOfAPoint) {
  FrontEndInput in = wallFrame();
  in.last_depth(cv::Rect(60, 0, 60, 100)).setTo(3.f);  // a step at x = 60
  const std::vector<PointTrack> tracks = {{{30, 50}, {30, 50}}, {{59, 50}, {59, 50}}};
  const TrackPoints lifted = liftTracks(tracks, in.last_depth, in.T_cw_last, smallTestCamera(), DynamicOptions{});
  EXPECT_TRUE(lifted.points_w[0]);
  EXPECT_FALSE(lifted.points_w[1]);
  ASSERT_EQ(lifted.intervals.size(), 2u);
  EXPECT_FALSE(lifted.intervals[0]);  // it has a point
  ASSERT_TRUE(lifted.intervals[1]);
  EXPECT_FLOAT_EQ(lifted.intervals[1]->near_m, 2.0);
  // A still track is static for some depth of its interval: its residual (the lower bound) is 0.
  const auto residuals = residualsUnder(lifted, tracks, in.T_cw_last, in.T_cw_initial, smallTestCamera());
  ASSERT_TRUE(residuals[1]);
  EXPECT_NEAR(residuals[1]->norm(), 0.0, 1e-9);
  // Without interval errors the edge track has no residual.
  DynamicOptions no_intervals;
  no_intervals.reprojection.interval_errors = false;
  const TrackPoints points_only = liftTracks(tracks, in.last_depth, in.T_cw_last, smallTestCamera(), no_intervals);
  EXPECT_TRUE(points_only.intervals.empty());
  EXPECT_FALSE(residualsUnder(points_only, tracks, in.T_cw_last, in.T_cw_initial, smallTestCamera())[1]);
}

}  // namespace
}  // namespace amos::dynamic
