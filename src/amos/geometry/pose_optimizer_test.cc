#include "amos/geometry/pose_optimizer.h"

#include <gtest/gtest.h>

#include <random>

#include "amos/core/error.h"
#include "amos/testing/test_camera.h"

namespace amos::geometry {
namespace {


// Random points in front of a camera at T_cw, observed with pixel noise; `outlier_fraction` of them are moved.
std::vector<PoseObservation> makeScene(const core::SE3& T_cw, int n, double noise_px, double outlier_fraction,
                                       bool with_right, unsigned seed, std::vector<bool>* is_outlier) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-1.5, 1.5), uz(0.8, 4.0), unit(0, 1), big(-60, 60);
  std::normal_distribution<double> noise(0, noise_px);
  const StereoProjection p = testing::testProjection();
  std::vector<PoseObservation> obs;
  const core::SE3 T_wc = T_cw.inverse();
  for (int i = 0; i < n; ++i) {
    const double z = uz(rng);
    const Eigen::Vector3d pc(ux(rng) * z * 0.5, ux(rng) * z * 0.4, z);
    PoseObservation o;
    o.point_w = T_wc * pc;
    o.pixel = {p.fx * pc.x() / z + p.cx + noise(rng), p.fy * pc.y() / z + p.cy + noise(rng)};
    o.u_right = with_right ? o.pixel.x() - p.bf / z + noise(rng) : -1;
    o.inv_sigma2 = 1.0;
    const bool bad = unit(rng) < outlier_fraction;
    if (bad) {
      o.pixel += Eigen::Vector2d(big(rng), big(rng));
      if (with_right) o.u_right = o.pixel.x() - p.bf / z;
    }
    if (is_outlier) is_outlier->push_back(bad);
    obs.push_back(o);
  }
  return obs;
}

core::SE3 truePose() {
  core::Vector6d xi;
  xi << 0.3, -0.2, 0.5, 0.1, -0.2, 0.05;
  return core::expSE3(xi);
}

core::SE3 perturbed(const core::SE3& T, double trans, double rot) {
  core::Vector6d d;
  d << trans, -trans * 0.5, trans * 0.8, rot, -rot * 0.7, rot * 0.4;
  return core::expSE3(d) * T;
}

TEST(PoseOptimizer, RecoversPerturbedPoseWithOutliersRgbd) {
  const core::SE3 T = truePose();
  std::vector<bool> truth;
  const auto obs = makeScene(T, 400, 0.5, 0.2, true, 7, &truth);
  PoseOptimizerOptions options;
  const auto result = optimizePose(obs, perturbed(T, 0.05, 0.03), testing::testProjection(), options);
  EXPECT_LT(core::translationNorm(result.T_cw.inverse() * T), 0.003);
  EXPECT_LT(core::rotationAngle(result.T_cw.inverse() * T), 0.002);
  int agree = 0;
  for (std::size_t i = 0; i < obs.size(); ++i) agree += result.outlier[i] == truth[i];
  EXPECT_GT(agree, 390);
  EXPECT_GT(result.num_inliers, 280);
}

TEST(PoseOptimizer, RecoversPerturbedPoseMonocularResiduals) {
  const core::SE3 T = truePose();
  const auto obs = makeScene(T, 300, 0.5, 0.1, false, 11, nullptr);
  const auto result = optimizePose(obs, perturbed(T, 0.04, 0.02), testing::testProjection(), PoseOptimizerOptions{});
  EXPECT_LT(core::translationNorm(result.T_cw.inverse() * T), 0.005);
  EXPECT_LT(core::rotationAngle(result.T_cw.inverse() * T), 0.002);
}

TEST(PoseOptimizer, ExactDataGivesExactPose) {
  const core::SE3 T = truePose();
  const auto obs = makeScene(T, 100, 0.0, 0.0, true, 3, nullptr);
  const auto result = optimizePose(obs, perturbed(T, 0.02, 0.01), testing::testProjection(), PoseOptimizerOptions{});
  EXPECT_LT(core::translationNorm(result.T_cw.inverse() * T), 1e-7);
  EXPECT_LT(core::rotationAngle(result.T_cw.inverse() * T), 1e-8);
  EXPECT_EQ(result.num_inliers, 100);
}

TEST(PoseOptimizer, ConvergesFromFarStart) {
  // Quadratic convergence to the exact pose from 15 cm / 4.6 deg away checks the analytic Jacobian.
  const core::SE3 T = truePose();
  const auto obs = makeScene(T, 200, 0.0, 0.0, true, 5, nullptr);
  PoseOptimizerOptions options;
  options.iterations_per_round = 20;
  const auto result = optimizePose(obs, perturbed(T, 0.15, 0.08), testing::testProjection(), options);
  EXPECT_LT(core::translationNorm(result.T_cw.inverse() * T), 1e-6);
}

TEST(PoseOptimizer, BadOptionsThrow) {
  PoseOptimizerOptions options;
  options.chi2_mono = 0;
  EXPECT_THROW(options.check(), core::Error);
}

}  // namespace
}  // namespace amos::geometry
