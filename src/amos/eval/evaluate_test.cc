#include "amos/eval/evaluate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/core/error.h"

namespace amos::eval {
namespace {

std::vector<io::StampedPose> circle(double rate, double duration, double t0) {
  std::vector<io::StampedPose> poses;
  for (int k = 0; k <= static_cast<int>(std::lround(rate * duration)); ++k) {
    const double t = k / rate;
    io::StampedPose p;
    p.timestamp = t0 + t;
    p.T_wc = core::expSE3((core::Vector6d() << std::cos(0.5 * t), 0.2 * std::sin(t), std::sin(0.5 * t), 0, 0.5 * t, 0)
                              .finished());
    poses.push_back(p);
  }
  return poses;
}

TEST(Evaluate, ScaledEstimateNeedsSim3) {
  const auto gt = circle(100, 8, 50.0);
  auto est = circle(30, 8, 50.0);
  const core::SE3 frame = core::expSE3((core::Vector6d() << 1, 2, 3, 0.1, -0.2, 0.3).finished());
  for (auto& p : est) {
    p.T_wc = frame * p.T_wc;
    p.T_wc.translation() *= 0.4;  // monocular-like scale
  }
  const EvaluationResult rigid = evaluate(gt, est);
  EvaluationOptions options;
  options.sim3 = true;
  const EvaluationResult similar = evaluate(gt, est, options);
  EXPECT_GT(rigid.ate_rmse_m, 0.1);
  EXPECT_NEAR(similar.alignment.scale, 2.5, 0.01);
  EXPECT_LT(similar.ate_rmse_m, 0.01);  // 100 Hz ground truth vs 30 Hz stamps: up to 5 ms apart
  EXPECT_LT(similar.rpe_trans_rmse_m, 0.01);  // the alignment scale is applied to the relative motions too
  EXPECT_EQ(similar.ate_pairs, est.size());
}

TEST(Evaluate, JsonHasTheAgreedKeysAndNullForMissingRpe) {
  const auto gt = circle(100, 8, 50.0);
  const auto est = circle(30, 0.5, 52.0);  // shorter than the 1 s RPE delta
  const EvaluationResult r = evaluate(gt, est);
  const nlohmann::json j = toJson(r);
  for (const char* key : {"ate_rmse_m", "ate_mean_m", "ate_median_m", "ate_max_m", "ate_pairs", "rpe_trans_rmse_m",
                          "rpe_rot_rmse_deg", "rpe_pairs", "alignment"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["ate_pairs"].get<std::size_t>(), est.size());
  EXPECT_TRUE(j["rpe_trans_rmse_m"].is_null());
  EXPECT_EQ(j["rpe_pairs"].get<std::size_t>(), 0u);
  EXPECT_EQ(j["alignment"]["type"], "se3");
  EXPECT_EQ(j["alignment"]["rotation"].size(), 9u);
  // Round trip through text stays valid JSON.
  EXPECT_EQ(nlohmann::json::parse(j.dump())["ate_pairs"], j["ate_pairs"]);
}

TEST(Evaluate, DisjointTimeRangesAreAnError) {
  const auto gt = circle(100, 2, 50.0);
  const auto est = circle(30, 2, 80.0);
  try {
    evaluate(gt, est);
    FAIL() << "no error for trajectories that do not overlap in time";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("ground-truth pose within"), std::string::npos) << e.what();
  }
}

TEST(Evaluate, AnEmptyTrajectoryIsNamedEmptyNotAWrongTimeOffset) {
  const auto poses = circle(50, 2, 50.0);
  auto errorOf = [](const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est) {
    try {
      evaluate(gt, est);
    } catch (const core::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(errorOf({}, poses), "the ground truth has no pose to compare with");
  EXPECT_EQ(errorOf(poses, {}), "the estimate has no pose to evaluate");
}

TEST(Evaluate, OptionsAreChecked) {
  EvaluationOptions options;
  options.rpe_delta_s = 0;
  EXPECT_THROW(options.check(), core::Error);
  options = {};
  options.max_time_difference_s = -1;
  EXPECT_THROW(options.check(), core::Error);
}

}  // namespace
}  // namespace amos::eval
