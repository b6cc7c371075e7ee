#include "amos/dynamic/initial_pose_models.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "amos/dynamic/test_scenes.h"

namespace amos::dynamic {
namespace {

core::SE3 pose(double tx, double ty, double tz, double rx, double ry, double rz) {
  core::Vector6d xi;
  xi << tx, ty, tz, rx, ry, rz;
  return core::expSE3(xi);
}

// n world points in front of the camera at T_cw, observed with 0.5 px noise.
PoseCorrespondences observe(const core::SE3& T_cw, const core::PinholeCamera& cam, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(20, 620), v(20, 460), z(1.0, 5.0);
  std::normal_distribution<double> noise(0.0, 0.5);
  PoseCorrespondences c;
  for (int i = 0; i < n; ++i) {
    const double zi = z(rng);
    const Eigen::Vector3d p_c = cam.backProject(u(rng), v(rng), zi);
    c.points_w.push_back(T_cw.inverse() * p_c);
    c.pixels.push_back(cam.project(p_c) + Eigen::Vector2d(noise(rng), noise(rng)));
  }
  return c;
}

// n noise-free correspondences at depth z in the pixel box [u0, u1) x [v0, v1), seen by a camera at T_cw: a compact
// group (a mover, or the static world seen between people).
PoseCorrespondences observePacked(const core::SE3& T_cw, const core::PinholeCamera& cam, int n, double u0, double u1,
                                  double v0, double v1, double z, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(u0, u1), v(v0, v1);
  PoseCorrespondences c;
  for (int i = 0; i < n; ++i) {
    const double x = u(rng), y = v(rng);
    const Eigen::Vector3d p_c = cam.backProject(x, y, z);
    c.points_w.push_back(T_cw.inverse() * p_c);
    c.pixels.push_back(cam.project(p_c));
  }
  return c;
}

double poseError(const core::SE3& a, const core::SE3& b) { return core::translationNorm(a.inverse() * b); }

TEST(InitialPoseModels, EveryKthThinsToAtMostTheMaximumInOrder) {
  std::vector<std::size_t> items(1000);
  for (std::size_t i = 0; i < items.size(); ++i) items[i] = 3 * i;
  const std::vector<std::size_t> thinned = everyKth(items, 300);  // stride 4: 250 items
  ASSERT_EQ(thinned.size(), 250u);
  for (std::size_t k = 0; k < thinned.size(); ++k) EXPECT_EQ(thinned[k], items[4 * k]);
  EXPECT_EQ(everyKth(items, 0), items);     // 0 = all
  EXPECT_EQ(everyKth(items, 1000), items);  // not more than there are
  EXPECT_EQ(everyKth(items, 1).size(), 1u);
  EXPECT_TRUE(everyKth({}, 300).empty());
}

TEST(InitialPoseModels, ConstantVelocityRepeatsTheLastMotion) {
  const core::SE3 motion = pose(0.01, -0.02, 0.03, 0.01, 0.02, -0.005);
  const core::SE3 T0 = pose(0.3, 0.1, -0.2, 0.1, 0.2, 0.3);
  const core::SE3 T1 = motion * T0, T2 = motion * T1;
  const core::SE3 predicted = constantVelocityPose(T1, velocityFrom(T1, T0));
  EXPECT_LT((predicted.matrix() - T2.matrix()).norm(), 1e-12);
}

TEST(InitialPoseModels, SelectionPicksTheUncorruptedModel) {
  const core::PinholeCamera cam = testCamera();
  const core::SE3 truth = pose(0.1, 0.0, 0.05, 0.02, -0.03, 0.01);
  const PoseCorrespondences common = observe(truth, cam, 200, 1);
  const std::vector<core::SE3> corrupted = {pose(0, 0, 0, 0, 0.035, 0) * truth,  // 2 deg off
                                            pose(0.1, 0, 0, 0, 0, 0) * truth};   // 10 cm off
  for (int correct = 0; correct < 3; ++correct) {
    std::vector<PoseCandidate> candidates(3);
    int next_bad = 0;
    for (int i = 0; i < 3; ++i) {
      candidates[i].model = static_cast<PoseModel>(i);
      candidates[i].valid = true;
      candidates[i].T_cw = i == correct ? truth : corrupted[next_bad++];
    }
    const InitialPoseResult r = selectInitialPose(candidates, common, cam, InitialPoseOptions{});
    ASSERT_TRUE(r.ok);
    EXPECT_EQ(static_cast<int>(r.model), correct);
    EXPECT_GT(r.candidates[correct].common_inliers, 190);
    for (int i = 0; i < 3; ++i)
      if (i != correct) {
        EXPECT_LT(r.candidates[i].common_inliers, 20) << i;
      }
  }
  // An invalid candidate is never chosen, however good its pose.
  std::vector<PoseCandidate> candidates(2);
  candidates[0].T_cw = truth;
  candidates[1].valid = true;
  candidates[1].T_cw = corrupted[0];
  EXPECT_EQ(selectInitialPose(candidates, common, cam, InitialPoseOptions{}).T_cw.matrix(), corrupted[0].matrix());
}

// Dynamic.InitialPose.selectByCoverage: of two candidates, one explains 150 correspondences packed in one corner of
// the image (a mover), the other 80 spread over it (the static world). By number the first wins, by coverage the
// second.
TEST(InitialPoseModels, SelectionByCoveragePrefersTheSpreadInliers) {
  const core::PinholeCamera cam = testCamera();
  const core::SE3 T_static = pose(0.01, 0, 0, 0, 0.01, 0), T_mover = pose(-0.05, 0.02, 0, 0, -0.03, 0);
  PoseCorrespondences common = observe(T_static, cam, 80, 3);
  common.append(observePacked(T_mover, cam, 150, 20, 140, 20, 120, 1.5, 5));
  std::vector<PoseCandidate> candidates(2);
  candidates[0] = {PoseModel::kReferenceKeyframe, true, T_mover};
  candidates[1] = {PoseModel::kLastFrame, true, T_static};
  InitialPoseOptions options;
  options.select_by_coverage = false;
  const InitialPoseResult by_number = selectInitialPose(candidates, common, cam, options);
  EXPECT_EQ(by_number.model, PoseModel::kReferenceKeyframe);
  options.select_by_coverage = true;
  const InitialPoseResult by_coverage = selectInitialPose(candidates, common, cam, options);
  EXPECT_EQ(by_coverage.model, PoseModel::kLastFrame);
  EXPECT_GT(by_coverage.candidates[1].common_cells, 30);
  EXPECT_LE(by_coverage.candidates[0].common_cells, 4);
}

// ... but only among candidates with at least half the most inliers (PnpRansacOptions::coverage_min_support): a
// pose that gathers 40 inliers spread over the image (chance agreement in a crowd) does not beat 200 packed in a
// quarter of it (the static world seen between people).
TEST(InitialPoseModels, SelectionByCoverageNeedsHalfTheMostInliers) {
  const core::PinholeCamera cam = testCamera();
  const core::SE3 T_static = pose(0.01, 0, 0, 0, 0.01, 0), T_other = pose(-0.05, 0.02, 0, 0, -0.03, 0);
  PoseCorrespondences common = observe(T_other, cam, 40, 3);
  common.append(observePacked(T_static, cam, 200, 20, 300, 20, 220, 3.0, 5));
  std::vector<PoseCandidate> candidates(2);
  candidates[0] = {PoseModel::kReferenceKeyframe, true, T_static};
  candidates[1] = {PoseModel::kLastFrame, true, T_other};
  InitialPoseOptions options;
  options.select_by_coverage = true;
  const InitialPoseResult floored = selectInitialPose(candidates, common, cam, options);
  EXPECT_EQ(floored.model, PoseModel::kReferenceKeyframe);
  EXPECT_GT(floored.candidates[1].common_cells, floored.candidates[0].common_cells);  // the wider one, yet not chosen
  options.pnp.coverage_min_support = 0;  // coverage alone
  EXPECT_EQ(selectInitialPose(candidates, common, cam, options).model, PoseModel::kLastFrame);
}

// Model 2's tracks without those that start on the last frame's movers (Dynamic.Temporal.excludeFromFits).
TEST(InitialPoseModels, TracksOffMaskDropsTheTracksStartingOnTheLastMask) {
  cv::Mat mask(480, 640, CV_8U, cv::Scalar(0));
  cv::rectangle(mask, cv::Rect(100, 100, 50, 50), cv::Scalar(255), cv::FILLED);
  std::vector<PointTrack> tracks = {{{120, 120}, {300, 300}, 0},   // starts on the mover (ends off it)
                                    {{300, 300}, {120, 120}, 1},   // ends on it: kept
                                    {{149, 149}, {149, 149}, 2},   // on its last pixel
                                    {{151, 151}, {152, 152}, 3}};  // beside it
  const std::vector<PointTrack> kept = tracksOffMask(tracks, mask);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].source_index, 1);
  EXPECT_EQ(kept[1].source_index, 3);
  EXPECT_EQ(tracksOffMask(tracks, cv::Mat()).size(), 4u);  // no mask (first frame, mode none): all of them
}

TEST(InitialPoseModels, EstimateRunsPnpPerModelAndKeepsTheBest) {
  const core::PinholeCamera cam = testCamera();
  const core::SE3 T_cw_last = pose(0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  const core::SE3 truth = pose(0.03, 0.0, 0.01, 0.0, 0.01, 0.0);
  const core::SE3 wrong_velocity = pose(-0.2, 0.1, 0.0, 0.05, 0.0, 0.0);
  // Keyframe correspondences consistent with a wrong pose (e.g. tracks locked onto a moving crowd).
  const PoseCorrespondences bad = observe(pose(0.15, 0.0, 0.0, 0.0, 0.0, 0.04), cam, 80, 2);
  const PoseCorrespondences good = observe(truth, cam, 150, 3);
  InitialPoseResult r = estimateInitialPose(bad, good, T_cw_last, wrong_velocity, cam, InitialPoseOptions{});
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.model, PoseModel::kLastFrame);
  EXPECT_LT(poseError(r.T_cw, truth), 0.01);
  EXPECT_EQ(r.common_size, 230);
  EXPECT_EQ(r.candidates.size(), 3u);
  EXPECT_TRUE(r.candidates[0].valid);                                         // PnP succeeds on its own (wrong) data...
  EXPECT_LT(r.candidates[0].common_inliers, r.candidates[1].common_inliers);  // ...but loses on the common set

  r = estimateInitialPose(good, bad, T_cw_last, wrong_velocity, cam, InitialPoseOptions{});
  EXPECT_EQ(r.model, PoseModel::kReferenceKeyframe);
  EXPECT_LT(poseError(r.T_cw, truth), 0.01);

  // Too few correspondences for PnP in either set: the constant-velocity prediction wins on their union.
  const core::SE3 velocity = truth * T_cw_last.inverse();
  const PoseCorrespondences few_a = observe(truth, cam, 10, 4), few_b = observe(truth, cam, 12, 5);
  r = estimateInitialPose(few_a, few_b, T_cw_last, velocity, cam, InitialPoseOptions{});
  ASSERT_TRUE(r.ok);
  EXPECT_FALSE(r.candidates[0].valid);
  EXPECT_FALSE(r.candidates[1].valid);
  EXPECT_EQ(r.model, PoseModel::kConstantVelocity);
  EXPECT_EQ(r.candidates[2].common_inliers, 22);
  // No velocity and no PnP: nothing to offer.
  EXPECT_FALSE(estimateInitialPose(few_a, few_b, T_cw_last, std::nullopt, cam, InitialPoseOptions{}).ok);
}

TEST(InitialPoseModels, KeyframeModelTracksKeypointsByLkAndSolvesThePose) {
  // A textured fronto-parallel wall at 2 m; the camera slides 1 cm to the right, so the image shifts left by
  // fx * 0.01 / 2 = 2.68 px.
  const core::PinholeCamera cam = testCamera();
  cv::Mat texture(480, 640, CV_8U);
  cv::randu(texture, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  const double shift = -cam.fx() * 0.01 / 2.0;
  cv::Mat current;
  const cv::Mat A = (cv::Mat_<double>(2, 3) << 1, 0, shift, 0, 1, 0);
  cv::warpAffine(texture, current, A, texture.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  std::vector<cv::Point2f> pixels;
  std::vector<Eigen::Vector3d> points_w;
  for (int v = 40; v < 440; v += 25)
    for (int u = 40; u < 600; u += 25) {
      pixels.emplace_back(u, v);
      points_w.push_back(cam.backProject(u, v, 2.0));  // keyframe at the world origin
    }
  CornerTrackingOptions tracking;
  const FramePairPyramids pyramids = buildPyramids(texture, current, tracking);
  const PoseCorrespondences c = keyframeCorrespondences(pyramids, pixels, points_w, cam, tracking);
  EXPECT_GT(c.size(), pixels.size() * 9 / 10);
  const PoseCandidate candidate = poseFromCorrespondences(PoseModel::kReferenceKeyframe, c, cam, InitialPoseOptions{});
  ASSERT_TRUE(candidate.valid);
  const core::SE3 truth = pose(-0.01, 0, 0, 0, 0, 0);  // T_cw of a camera at x = +1 cm
  EXPECT_LT(poseError(candidate.T_cw, truth), 0.002);
}

}  // namespace
}  // namespace amos::dynamic
