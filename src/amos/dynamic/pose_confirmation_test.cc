#include "amos/dynamic/pose_confirmation.h"

#include <gtest/gtest.h>

#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

// The small test camera looking at a wall 2 m away, with the same pose in both frames: 81 still tracks in cluster 0
// (x < 60) and 20 in cluster 1 that moved 2 px, too little for a candidate (3 px) and plenty under a clean refit.
struct ConfirmationScene {
  std::vector<PointTrack> tracks;
  FrontEndInput in;
  cv::Mat decision_map;
};

ConfirmationScene slowMoverScene() {
  ConfirmationScene scene;
  for (int y = 10; y <= 90; y += 10)
    for (int x = 6; x <= 54; x += 6) scene.tracks.push_back({cv::Point2f(x, y), cv::Point2f(x, y)});
  for (int y = 20; y <= 80; y += 20)
    for (int x = 66; x <= 114; x += 12) scene.tracks.push_back({cv::Point2f(x, y), cv::Point2f(x + 2, y)});
  scene.in = wallFramePair({120, 100}, 2.f);
  scene.decision_map = cv::Mat(100, 120, CV_32S, cv::Scalar(0));
  scene.decision_map(cv::Rect(60, 0, 60, 100)).setTo(1);
  return scene;
}

// The scene through the candidate stage and then the confirmation (whose diagnostics are kept).
struct Confirmed {
  CandidateScoring candidates;
  PoseConfirmation confirmation;
  DynamicDiagnostics diag;
};

Confirmed confirm(const ConfirmationScene& scene, const DynamicOptions& options) {
  Confirmed c;
  DynamicDiagnostics scoring_diag;
  const PriorRegions no_prior;
  c.candidates =
      scoreCandidates(scene.tracks, scene.in, {scene.decision_map, 2, no_prior}, smallTestCamera(), options, scoring_diag);
  c.confirmation = confirmUnderRefittedPose(scene.tracks, c.candidates, scene.in.T_cw_last, scene.in.T_cw_initial,
                                            smallTestCamera(), options.reprojection, c.diag);
  return c;
}

TEST(PoseConfirmation, ASlowMoverIsConfirmedUnderTheRefittedPose) {
  const ConfirmationScene scene = slowMoverScene();
  const DynamicOptions options;
  const Confirmed c = confirm(scene, options);
  ASSERT_FALSE(c.candidates.cluster_scores[1].candidate);
  ASSERT_TRUE(c.confirmation.refit.ok);
  EXPECT_TRUE(c.diag.pose_refit_ok);
  EXPECT_EQ(c.diag.pose_refit_points, 101);  // no candidates: every track is offered
  EXPECT_EQ(c.diag.pose_refit_inliers, 81);  // and the movers fall out
  EXPECT_LT(c.confirmation.refit.T_cw.translation().norm(), 1e-6);
  EXPECT_EQ(c.confirmation.confirmed, (std::vector<bool>{false, true}));
  EXPECT_EQ(c.diag.candidate_clusters, 1);
  EXPECT_EQ(c.confirmation.static_bar_px, c.diag.confirm_threshold_px);
  EXPECT_EQ(c.confirmation.static_bar_px, confirmThreshold(c.confirmation.refit, options.reprojection));
  EXPECT_EQ(c.confirmation.fit_tracks, c.candidates.outside_candidates);
  ASSERT_EQ(c.confirmation.residuals.size(), scene.tracks.size());
  EXPECT_NEAR(c.confirmation.residuals.back()->x(), 2.0, 1e-6);
}

TEST(PoseConfirmation, WhenTheLastMaskLeavesTooFewTracksTheRefitDoesWithoutIt) {
  ConfirmationScene scene = slowMoverScene();
  scene.in.last_mask = cv::Mat(100, 120, CV_8U, cv::Scalar(255));  // every track started on a mover
  const Confirmed c = confirm(scene, DynamicOptions{});
  ASSERT_EQ(c.candidates.outside_candidates, std::vector<bool>(101, false));
  EXPECT_TRUE(c.confirmation.refit.ok);
  EXPECT_EQ(c.confirmation.fit_tracks, c.candidates.outside_now);
  EXPECT_EQ(c.confirmation.confirmed, (std::vector<bool>{false, true}));
}

TEST(PoseConfirmation, WithoutTheRefitTheInitialPoseAndCandidateThresholdJudge) {
  const ConfirmationScene scene = slowMoverScene();
  DynamicOptions options;
  options.reprojection.refit_pose = false;
  const Confirmed c = confirm(scene, options);
  EXPECT_FALSE(c.confirmation.refit.ok);
  EXPECT_FALSE(c.diag.pose_refit_ok);
  EXPECT_TRUE(c.confirmation.refit.T_cw.isApprox(scene.in.T_cw_initial));
  EXPECT_TRUE(c.confirmation.confirm_scores.empty());
  EXPECT_EQ(c.confirmation.confirmed, (std::vector<bool>{false, false}));
  EXPECT_EQ(c.confirmation.static_bar_px, options.reprojection.candidate_threshold_px);
  EXPECT_EQ(c.diag.candidate_clusters, 0);
  EXPECT_EQ(c.confirmation.fit_tracks, c.candidates.outside_candidates);
}

}  // namespace
}  // namespace amos::dynamic
