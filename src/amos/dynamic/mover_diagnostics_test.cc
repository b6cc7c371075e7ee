#include "amos/dynamic/mover_diagnostics.h"

#include <gtest/gtest.h>

namespace amos::dynamic {
namespace {

// A 40x40 frame in two clusters (left / right half); a mover fills the left half's top 20 rows.
FrontEndResult frame(bool left_dynamic, int tracks_on_mover) {
  FrontEndResult out;
  out.mask = cv::Mat(40, 40, CV_8U, cv::Scalar(0));
  out.cluster_map = cv::Mat(40, 40, CV_32S, cv::Scalar(1));
  out.cluster_map.colRange(0, 20).setTo(0);
  out.cluster_scores.resize(2);
  out.cluster_scores[0].points = tracks_on_mover;
  out.cluster_scores[0].equivalent_px = 5.0;
  out.cluster_scores[0].candidate = left_dynamic;
  out.dynamic_cluster = {left_dynamic, false};
  if (left_dynamic) out.mask(cv::Rect(0, 0, 20, 20)).setTo(255);
  for (int i = 0; i < tracks_on_mover; ++i) {
    out.tracks.push_back({{5.f + i, 5.f}, {6.f + i, 5.f}, i});
    out.reprojection_error_px.emplace_back(4.0 + i);
    out.judged_error_px.emplace_back(3.0);
    out.epipolar_distance_px.push_back(i == 0 ? 10.0 : 0.5);
  }
  return out;
}

cv::Mat moverIds() {
  cv::Mat ids(40, 40, CV_16U, cv::Scalar(0));
  ids(cv::Rect(0, 0, 20, 20)).setTo(7);
  return ids;
}

TEST(MoverDiagnostics, FoundMoverReportsItsTracksAndCluster) {
  std::vector<bool> moving(8, false);
  moving[7] = true;
  const auto d = diagnoseMovers(frame(true, 3), moverIds(), moving, DynamicOptions{});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].id, 7);
  EXPECT_EQ(d[0].pixels, 400);
  EXPECT_EQ(d[0].marked, 400);
  EXPECT_EQ(d[0].tracks, 3);
  EXPECT_EQ(d[0].tracks_scored, 3);
  EXPECT_DOUBLE_EQ(d[0].median_initial_px, 5.0);
  EXPECT_EQ(d[0].epipolar_violators, 1);
  ASSERT_EQ(d[0].clusters.size(), 1u);
  EXPECT_EQ(d[0].clusters[0].cluster_px, 800);
  EXPECT_TRUE(d[0].clusters[0].dynamic);
  EXPECT_EQ(d[0].cause, "found");
}

TEST(MoverDiagnostics, BaselinePointsOnTheMoverAreCounted) {
  std::vector<bool> moving(8, false);
  moving[7] = true;
  FrontEndResult out = frame(true, 3);
  // Two points on the mover (one beyond the bar), one on the static right half.
  out.baseline_points = {{{5.f, 5.f}, {9.f, 5.f}, 4.0, true}, {{8.f, 8.f}, {8.5f, 8.f}, 0.5, false},
                         {{30.f, 5.f}, {30.f, 5.f}, 0.1, false}};
  const auto d = diagnoseMovers(out, moverIds(), moving, DynamicOptions{});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].baseline_points, 2);
  EXPECT_EQ(d[0].baseline_moving, 1);
  EXPECT_DOUBLE_EQ(d[0].median_baseline_px, 4.0);  // the upper median of two, as for the other medians
}

TEST(MoverDiagnostics, CausesOfAMiss) {
  std::vector<bool> moving(8, false);
  moving[7] = true;
  EXPECT_EQ(diagnoseMovers(frame(false, 1), moverIds(), moving, DynamicOptions{})[0].cause, "no-tracks");
  EXPECT_EQ(diagnoseMovers(frame(false, 4), moverIds(), moving, DynamicOptions{})[0].cause, "below-threshold");
  FrontEndResult mask_missed = frame(true, 4);
  mask_missed.mask.setTo(0);
  EXPECT_EQ(diagnoseMovers(mask_missed, moverIds(), moving, DynamicOptions{})[0].cause, "mask");
  // At rest: not diagnosed.
  EXPECT_TRUE(diagnoseMovers(frame(false, 4), moverIds(), std::vector<bool>(8, false), DynamicOptions{}).empty());
}

}  // namespace
}  // namespace amos::dynamic
