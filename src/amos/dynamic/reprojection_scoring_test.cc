#include "amos/dynamic/reprojection_scoring.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "amos/core/error.h"
#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

TEST(CauchyRho, IsQuadraticForSmallErrorsAndLogarithmicForLargeOnes) {
  EXPECT_DOUBLE_EQ(cauchyRho(0.0, 2.0), 0.0);
  EXPECT_NEAR(cauchyRho(0.01, 1.0), 0.01, 1e-4);  // rho(s) ~ s for s << c^2
  EXPECT_NEAR(cauchyRho(1e4, 1.0), std::log(1e4 + 1), 1e-9);
  for (double e : {0.0, 0.5, 3.0, 40.0}) EXPECT_NEAR(cauchyEquivalentError(cauchyRho(e * e, 1.5), 1.5), e, 1e-9);
}

TEST(ScoreClusters, CauchyMeanIgnoresAnOutlier) {
  // Ten static points at 1 px and one gross mismatch at 100 px: the plain RMS would be ~30 px.
  std::vector<std::optional<double>> errors(10, 1.0);
  errors.push_back(100.0);
  const std::vector<int> clusters(errors.size(), 0);
  ReprojectionOptions options;
  const std::vector<ClusterScore> scores = scoreClusters(errors, clusters, 1, options);
  ASSERT_EQ(scores.size(), 1u);
  EXPECT_EQ(scores[0].points, 11);
  EXPECT_LT(scores[0].equivalent_px, options.candidate_threshold_px);
  EXPECT_FALSE(scores[0].candidate);
  // The plain mean of squared errors would have made it a candidate.
  EXPECT_GT(std::sqrt((10 * 1.0 + 100.0 * 100.0) / 11), 10 * options.candidate_threshold_px);
  // Half the points moving by 6 px makes the cluster a candidate.
  std::vector<std::optional<double>> moving(6, 1.0);
  moving.resize(12, 6.0);
  EXPECT_TRUE(scoreClusters(moving, std::vector<int>(12, 0), 1, options)[0].candidate);
}

TEST(ScoreClusters, SkipsPointsWithoutErrorOrClusterAndSmallClusters) {
  const std::vector<std::optional<double>> errors = {10.0, 10.0, std::nullopt, 10.0, 10.0, 10.0};
  const std::vector<int> clusters = {0, 0, 0, -1, 1, 1};
  ReprojectionOptions options;
  options.min_points_per_cluster = 3;
  const std::vector<ClusterScore> scores = scoreClusters(errors, clusters, 3, options);
  EXPECT_EQ(scores[0].points, 2);
  EXPECT_EQ(scores[1].points, 2);
  EXPECT_EQ(scores[2].points, 0);
  for (const ClusterScore& s : scores) EXPECT_FALSE(s.candidate);  // too few points to judge
  options.min_points_per_cluster = 2;
  EXPECT_TRUE(scoreClusters(errors, clusters, 3, options)[0].candidate);
  EXPECT_THROW(scoreClusters(errors, {0, 0}, 3, options), core::Error);
}

// Two frames of a synthetic room: a wall at 3 m (cluster 0), a cabinet at 2 m (cluster 1), a box at 1.5 m
// (cluster 2) that moves 5 cm sideways between the frames while the camera moves 2 cm and turns 0.5 deg.
struct TwoFrameScene {
  cv::Mat last_depth;
  core::SE3 T_cw_last, T_cw_current;
  std::vector<PointTrack> tracks;
  std::vector<int> cluster;
};

TwoFrameScene makeScene(const core::PinholeCamera& cam, double box_motion_x = 0.05) {
  TwoFrameScene s;
  s.last_depth = cv::Mat(480, 640, CV_32F, cv::Scalar(3.f));
  s.last_depth(cv::Rect(400, 0, 240, 480)).setTo(2.f);
  s.last_depth(cv::Rect(120, 200, 160, 160)).setTo(1.5f);
  core::Vector6d xi_last, xi_cur;
  xi_last << 0.1, -0.05, 0.2, 0.02, -0.01, 0.03;
  s.T_cw_last = core::expSE3(xi_last);
  xi_cur << 0.02, 0.0, 0.0, 0.0, 0.5 * M_PI / 180, 0.0;
  s.T_cw_current = core::expSE3(xi_cur) * s.T_cw_last;
  const Eigen::Vector3d box_motion_w(box_motion_x, 0.0, 0.0);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.2);
  for (int v = 20; v < 460; v += 16)
    for (int u = 20; u < 620; u += 16) {
      const float z = s.last_depth.at<float>(v, u);
      const int cluster = z == 1.5f ? 2 : (z == 2.f ? 1 : 0);
      Eigen::Vector3d p_w = s.T_cw_last.inverse() * cam.backProject(u, v, z);
      if (cluster == 2) p_w += box_motion_w;
      const Eigen::Vector3d p_c = s.T_cw_current * p_w;
      const Eigen::Vector2d px = cam.project(p_c);
      s.tracks.push_back({cv::Point2f(u, v), cv::Point2f(px.x() + noise(rng), px.y() + noise(rng))});
      s.cluster.push_back(cluster);
    }
  return s;
}

TEST(ReprojectionScoring, MovingClusterScoresHighStaticClustersLow) {
  const core::PinholeCamera cam = testCamera();
  const TwoFrameScene scene = makeScene(cam);
  ReprojectionOptions options;
  const auto points = backProjectTracks(scene.tracks, scene.last_depth, scene.T_cw_last, cam, options);
  const auto errors = reprojectionErrors(scene.tracks, points, scene.T_cw_current, cam);
  const std::vector<ClusterScore> scores = scoreClusters(errors, scene.cluster, 3, options);
  EXPECT_GT(scores[0].points, 100);
  EXPECT_GT(scores[2].points, 40);
  EXPECT_LT(scores[0].equivalent_px, 1.0);
  EXPECT_LT(scores[1].equivalent_px, 1.0);
  // 5 cm at ~1.5 m is ~18 px: the box is a candidate, the wall and the cabinet are not.
  EXPECT_GT(scores[2].equivalent_px, 10.0);
  EXPECT_FALSE(scores[0].candidate);
  EXPECT_FALSE(scores[1].candidate);
  EXPECT_TRUE(scores[2].candidate);
}

TEST(ReprojectionScoring, BackProjectionFollowsEq6AndSkipsInvalidOrEdgeDepth) {
  const core::PinholeCamera cam = testCamera();
  const TwoFrameScene scene = makeScene(cam);
  cv::Mat depth = scene.last_depth.clone();
  depth.at<float>(100, 100) = 0.f;  // hole next to the track at (101, 100)
  const std::vector<PointTrack> tracks = {
      {{101.f, 100.f}, {0.f, 0.f}},   // neighbour of a hole
      {{400.f, 100.f}, {0.f, 0.f}},   // on the wall/cabinet depth edge (x = 399 | 400)
      {{300.f, 100.f}, {0.f, 0.f}},   // clean wall point
      {{639.f, 100.f}, {0.f, 0.f}}};  // on the image edge: no 3x3 neighbourhood
  const auto points = backProjectTracks(tracks, depth, scene.T_cw_last, cam, ReprojectionOptions{});
  EXPECT_FALSE(points[0].has_value());
  EXPECT_FALSE(points[1].has_value());
  ASSERT_TRUE(points[2].has_value());
  EXPECT_FALSE(points[3].has_value());
  const Eigen::Vector3d expected = scene.T_cw_last.inverse() * cam.backProject(300, 100, 3.0);
  EXPECT_NEAR((*points[2] - expected).norm(), 0.0, 1e-9);
  // Back into the last frame it lands on its pixel.
  EXPECT_NEAR((cam.project(scene.T_cw_last * *points[2]) - Eigen::Vector2d(300, 100)).norm(), 0.0, 1e-6);
}

TEST(ReprojectionScoring, ResidualsAreTheVectorsBehindTheErrors) {
  const core::PinholeCamera cam = testCamera();
  const TwoFrameScene scene = makeScene(cam);
  const auto points = backProjectTracks(scene.tracks, scene.last_depth, scene.T_cw_last, cam, ReprojectionOptions{});
  const auto errors = reprojectionErrors(scene.tracks, points, scene.T_cw_current, cam);
  const auto residuals = reprojectionResiduals(scene.tracks, points, scene.T_cw_current, cam);
  ASSERT_EQ(errors.size(), residuals.size());
  for (std::size_t i = 0; i < errors.size(); ++i) {
    ASSERT_EQ(errors[i].has_value(), residuals[i].has_value());
    if (errors[i]) {
      EXPECT_DOUBLE_EQ(*errors[i], residuals[i]->norm());
    }
  }
}

// A slow mover (1.2 cm, ~4 px) among the tracks and an initial pose slid along the translation/rotation ambiguity
// (1.5 cm sideways against a compensating yaw, so that the far wall barely notices): the refit returns to the
// true pose, measures the 0.2 px noise, and leaves the mover with its full error.
TEST(ReprojectionScoring, RefitRecoversThePoseAndTheNoiseScaleDespiteAMover) {
  const core::PinholeCamera cam = testCamera();
  const TwoFrameScene scene = makeScene(cam, 0.012);
  ReprojectionOptions options;
  const auto points = backProjectTracks(scene.tracks, scene.last_depth, scene.T_cw_last, cam, options);
  core::Vector6d slide;
  slide << 0.015, 0.0, 0.0, 0.0, -0.015 / 3.0, 0.0;  // rho then phi: x against yaw at the wall's 3 m
  const core::SE3 initial = core::expSE3(slide) * scene.T_cw_current;
  const std::vector<bool> all(scene.tracks.size(), true);
  const PoseRefit refit = refitPose(scene.tracks, points, all, initial, cam, options);
  ASSERT_TRUE(refit.ok);
  EXPECT_LT(core::translationNorm(refit.T_cw * scene.T_cw_current.inverse()), 1e-3);
  EXPECT_GT(refit.sigma_px, 0.1);
  EXPECT_LT(refit.sigma_px, 0.35);
  EXPECT_LT(refit.inliers, refit.points);  // the box's tracks are outliers
  EXPECT_DOUBLE_EQ(confirmThreshold(refit, options), std::max(1.0, 5.0 * refit.sigma_px));
  const auto residuals = reprojectionResiduals(scene.tracks, points, refit.T_cw, cam);
  std::vector<std::optional<double>> errors(residuals.size());
  for (std::size_t i = 0; i < residuals.size(); ++i)
    if (residuals[i]) errors[i] = residuals[i]->norm();
  ReprojectionOptions confirm = options;
  confirm.candidate_threshold_px = confirmThreshold(refit, options);
  const std::vector<ClusterScore> scores = scoreClusters(errors, scene.cluster, 3, confirm);
  EXPECT_FALSE(scores[0].candidate);
  EXPECT_FALSE(scores[1].candidate);
  EXPECT_TRUE(scores[2].candidate);
  EXPECT_GT(scores[2].equivalent_px, 3.0);
}

TEST(ReprojectionScoring, RefitNeedsEnoughPoints) {
  const core::PinholeCamera cam = testCamera();
  const TwoFrameScene scene = makeScene(cam);
  ReprojectionOptions options;
  const auto points = backProjectTracks(scene.tracks, scene.last_depth, scene.T_cw_last, cam, options);
  std::vector<bool> few(scene.tracks.size(), false);
  for (std::size_t i = 0; i < 20; ++i) few[i] = true;
  const PoseRefit refit = refitPose(scene.tracks, points, few, scene.T_cw_current, cam, options);
  EXPECT_FALSE(refit.ok);
  EXPECT_LE(refit.points, 20);
  EXPECT_TRUE(refit.T_cw.isApprox(scene.T_cw_current));
  options.refit_min_points = 3;
  EXPECT_THROW(options.check(), core::Error);
}

TEST(ReprojectionScoring, DepthIntervalsSpanTheWindowAndOpenAtHoles) {
  // 2 m everywhere, a 1 m patch at x >= 50, a hole at (20, 80).
  cv::Mat depth(100, 100, CV_32F, cv::Scalar(2.0f));
  depth(cv::Rect(50, 0, 50, 100)).setTo(1.0f);
  depth.at<float>(80, 20) = 0.f;
  auto track = [](float x, float y) { return PointTrack{{x, y}, {x, y}}; };
  const std::vector<PointTrack> tracks = {track(20, 20), track(49, 20), track(21, 79), track(-5, 20)};
  const auto intervals = trackDepthIntervals(tracks, depth, 3, ReprojectionOptions{});
  ASSERT_EQ(intervals.size(), 4u);
  ASSERT_TRUE(intervals[0]);  // uniform: one depth
  EXPECT_DOUBLE_EQ(intervals[0]->near_m, 2.0);
  EXPECT_DOUBLE_EQ(intervals[0]->far_m, 2.0);
  ASSERT_TRUE(intervals[1]);  // on the step: both sides
  EXPECT_DOUBLE_EQ(intervals[1]->near_m, 1.0);
  EXPECT_DOUBLE_EQ(intervals[1]->far_m, 2.0);
  ASSERT_TRUE(intervals[2]);  // a hole in the window: open to infinity
  EXPECT_DOUBLE_EQ(intervals[2]->near_m, 2.0);
  EXPECT_TRUE(std::isinf(intervals[2]->far_m));
  EXPECT_FALSE(intervals[3]);  // outside the image
}

TEST(ReprojectionScoring, IntervalResidualIsTheDistanceFromTheRaysImage) {
  const core::PinholeCamera cam = testCamera();
  // The camera moves 5 cm right (T_cw translation -5 cm): a point at depth z shifts by -fx * 0.05 / z px.
  core::SE3 T_cw_current = core::SE3::Identity();
  T_cw_current.translation() = Eigen::Vector3d(-0.05, 0.0, 0.0);
  const cv::Point2f p(300.f, 200.f);
  auto shifted = [&](double z, double extra_px) {
    return PointTrack{p, {static_cast<float>(p.x - cam.fx() * 0.05 / z + extra_px), p.y}};
  };
  auto dy = [&](double z, double extra_px) {  // a mover: off the ray's image vertically
    return PointTrack{p, {static_cast<float>(p.x - cam.fx() * 0.05 / z), static_cast<float>(p.y + extra_px)}};
  };
  const std::vector<PointTrack> tracks = {shifted(1.5, 0), shifted(1.0, 0), shifted(2.0, 0), dy(1.5, 4.0),
                                          shifted(1.5, 0)};
  const DepthInterval one_to_two{1.0, 2.0}, near_only{1.8, 2.0}, open{1.0, std::numeric_limits<double>::infinity()};
  const std::vector<std::optional<DepthInterval>> intervals = {one_to_two, one_to_two, one_to_two, one_to_two,
                                                               near_only};
  const auto r = intervalResiduals(tracks, intervals, core::SE3::Identity(), T_cw_current, cam);
  ASSERT_EQ(r.size(), 5u);
  for (int i : {0, 1, 2}) {  // static at any depth of the interval: on the segment
    ASSERT_TRUE(r[i]);
    EXPECT_LT(r[i]->norm(), 1e-3) << i;
  }
  ASSERT_TRUE(r[3]);  // 4 px across the segment
  EXPECT_NEAR(r[3]->norm(), 4.0, 1e-3);
  ASSERT_TRUE(r[4]);  // static at 1.5 m, but the window only allows 1.8-2 m: the distance to the 1.8 m end
  EXPECT_NEAR(r[4]->norm(), cam.fx() * 0.05 * (1 / 1.5 - 1 / 1.8), 1e-3);
  // Open to infinity: the segment runs to the vanishing point (no shift), so a point at 10 m is static too.
  const auto far = intervalResiduals({shifted(10.0, 0)}, {open}, core::SE3::Identity(), T_cw_current, cam);
  ASSERT_TRUE(far[0]);
  EXPECT_LT(far[0]->norm(), 1e-3);
  // No interval, no residual.
  EXPECT_FALSE(intervalResiduals({shifted(1.5, 0)}, {std::nullopt}, core::SE3::Identity(), T_cw_current, cam)[0]);
}

}  // namespace
}  // namespace amos::dynamic
