#include "amos/eval/jitter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/eval/evaluate.h"

namespace amos::eval {
namespace {

constexpr double kFps = 30.0;

// A camera moving `step` metres per frame along x, looking along z.
std::vector<io::StampedPose> straightLine(int n, double step, double t0 = 100.0) {
  std::vector<io::StampedPose> poses;
  for (int k = 0; k < n; ++k) {
    io::StampedPose p;
    p.timestamp = t0 + k / kFps;
    p.T_wc.translation() = Eigen::Vector3d(step * k, 0.0, 1.0);
    poses.push_back(p);
  }
  return poses;
}

TEST(Jitter, AlternatingOffsetsGiveTwiceTheirSizePerFrame) {
  const double step = 0.002, a = 0.001;  // 2 mm per frame, +-1 mm across the motion
  const std::vector<io::StampedPose> gt = straightLine(101, step);
  std::vector<io::StampedPose> est = gt;
  for (std::size_t k = 0; k < est.size(); ++k) est[k].T_wc.translation().y() += (k % 2 == 0 ? a : -a);
  const JitterResult r = computeJitter(gt, est);
  ASSERT_EQ(r.steps.size(), 100u);
  EXPECT_EQ(r.gaps, 0u);
  EXPECT_NEAR(r.trans_m.rmse, 2 * a, 1e-9);
  EXPECT_NEAR(r.trans_m.median, 2 * a, 1e-9);
  EXPECT_NEAR(r.rot_deg.median, 0.0, 1e-6);
  EXPECT_NEAR(r.gt_step_median_m, step, 1e-9);
  const double est_step = std::hypot(step, 2 * a);
  EXPECT_NEAR(r.est_step_median_m, est_step, 1e-9);
  EXPECT_NEAR(r.gt_path_m, 100 * step, 1e-9);
  EXPECT_NEAR(r.est_path_m, 100 * est_step, 1e-9);
}

TEST(Jitter, OneLineGivesTheFiguresInMillimetres) {
  const std::vector<io::StampedPose> gt = straightLine(11, 0.002);
  std::vector<io::StampedPose> est = gt;
  for (std::size_t k = 0; k < est.size(); ++k) est[k].T_wc.translation().y() += (k % 2 == 0 ? 0.001 : -0.001);
  const std::string line = jitterLine(computeJitter(gt, est));
  EXPECT_NE(line.find("RPE trans rmse 2.00 mm, median 2.00 mm"), std::string::npos) << line;
  EXPECT_NE(line.find("ground truth 2.00 mm"), std::string::npos) << line;
  EXPECT_NE(line.find("(10 pairs)"), std::string::npos) << line;
  EXPECT_EQ(line.back(), '\n');
  EXPECT_NE(jitterLine(computeJitter(gt, {})).find("n/a"), std::string::npos);
}

TEST(Jitter, AlternatingRotationGivesTwiceItsAngle) {
  const double theta = 0.1 * M_PI / 180;  // +-0.1 deg about the optical axis
  const std::vector<io::StampedPose> gt = straightLine(60, 0.003);
  std::vector<io::StampedPose> est = gt;
  for (std::size_t k = 0; k < est.size(); ++k)
    est[k].T_wc.linear() = Eigen::AngleAxisd(k % 2 == 0 ? theta : -theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const JitterResult r = computeJitter(gt, est);
  ASSERT_EQ(r.steps.size(), 59u);
  EXPECT_NEAR(r.rot_deg.median, 0.2, 1e-9);
  EXPECT_NEAR(r.rot_deg.rmse, 0.2, 1e-9);
  // The step d seen from the first camera, rotated by +-theta: |(I - R(theta)) d| = 2 sin(theta / 2) |d|.
  EXPECT_NEAR(r.trans_m.median, 2 * std::sin(theta / 2) * 0.003, 1e-12);
  EXPECT_NEAR(r.est_path_m, r.gt_path_m, 1e-12);  // rotations do not change step lengths
}

TEST(Jitter, ExactEstimateInAnotherFrameHasNoJitter) {
  const std::vector<io::StampedPose> gt = straightLine(40, 0.004);
  std::vector<io::StampedPose> est = gt;
  const core::SE3 frame = core::expSE3((core::Vector6d() << 1, -2, 0.5, 0.3, 0.2, -0.1).finished());
  for (auto& p : est) {
    p.T_wc = frame * p.T_wc;
    p.timestamp += 0.004;  // within the association radius
  }
  const JitterResult r = computeJitter(gt, est);
  ASSERT_EQ(r.steps.size(), 39u);
  EXPECT_LT(r.trans_m.rmse, 1e-12);
  EXPECT_LT(r.rot_deg.rmse, 1e-5);  // acos near 1: about sqrt(2 eps) rad
  EXPECT_NEAR(r.est_path_m, r.gt_path_m, 1e-12);
}

TEST(Jitter, StretchesWithoutPosesAreLeftOutAndScaleMultipliesTheEstimate) {
  const std::vector<io::StampedPose> gt = straightLine(50, 0.002);
  std::vector<io::StampedPose> est;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    if (k >= 20 && k < 30) continue;  // tracking lost: no poses written
    io::StampedPose p = gt[k];
    p.T_wc.translation() *= 0.5;  // half scale
    est.push_back(p);
  }
  JitterOptions options;
  options.scale = 2.0;
  const JitterResult r = computeJitter(gt, est, options);
  EXPECT_EQ(r.gaps, 1u);
  EXPECT_EQ(r.steps.size(), 38u);  // 40 poses, 39 consecutive pairs, one across the gap
  EXPECT_LT(r.trans_m.rmse, 1e-12);
  EXPECT_NEAR(r.gt_path_m, 38 * 0.002, 1e-12);
  EXPECT_NEAR(r.est_path_m, r.gt_path_m, 1e-12);
}

TEST(Jitter, NoAssociatedPosesGiveNoSteps) {
  const JitterResult r = computeJitter(straightLine(10, 0.01, 0.0), straightLine(10, 0.01, 50.0));
  EXPECT_TRUE(r.steps.empty());
  EXPECT_TRUE(std::isnan(r.trans_m.rmse));
  EXPECT_TRUE(std::isnan(r.gt_step_median_m));
}

TEST(Jitter, IsPartOfTheEvaluationAndItsJson) {
  const std::vector<io::StampedPose> gt = straightLine(91, 0.002);
  std::vector<io::StampedPose> est = gt;
  for (std::size_t k = 0; k < est.size(); ++k) est[k].T_wc.translation().z() += (k % 2 == 0 ? 0.003 : -0.003);
  const EvaluationResult r = evaluate(gt, est);
  EXPECT_NEAR(r.jitter.trans_m.rmse, 0.006, 1e-9);
  const nlohmann::json j = toJson(r)["jitter"];
  EXPECT_NEAR(j["rpe1_trans_rmse_m"].get<double>(), 0.006, 1e-9);
  EXPECT_NEAR(j["rpe1_trans_median_m"].get<double>(), 0.006, 1e-9);
  EXPECT_NEAR(j["rpe1_rot_median_deg"].get<double>(), 0.0, 1e-6);
  EXPECT_NEAR(j["gt_step_median_m"].get<double>(), 0.002, 1e-9);
  EXPECT_NEAR(j["est_step_median_m"].get<double>(), std::hypot(0.002, 0.006), 1e-9);
  EXPECT_NEAR(j["gt_path_m"].get<double>(), 0.18, 1e-9);
  EXPECT_NEAR(j["est_path_m"].get<double>(), 90 * std::hypot(0.002, 0.006), 1e-9);
  EXPECT_EQ(j["pairs"].get<int>(), 90);
  for (const char* key : {"rpe1_rot_rmse_deg", "gaps"}) EXPECT_TRUE(j.contains(key)) << key;
}

}  // namespace
}  // namespace amos::eval
