#include "amos/eval/rpe.h"

#include <gtest/gtest.h>

#include <cmath>

namespace amos::eval {
namespace {

// A smooth camera path sampled at `rate` Hz over [0, duration]: moving along x at `speed` m/s, optionally
// yawing at `yaw_rate` rad/s.
std::vector<io::StampedPose> path(double rate, double duration, double speed, double yaw_rate) {
  std::vector<io::StampedPose> poses;
  const int n = static_cast<int>(std::lround(duration * rate));
  for (int k = 0; k <= n; ++k) {
    io::StampedPose p;
    p.timestamp = 1000.0 + k / rate;
    const double t = k / rate;
    p.T_wc = core::expSE3((core::Vector6d() << speed * t, 0.1 * std::sin(t), 0, 0, yaw_rate * t, 0).finished());
    poses.push_back(p);
  }
  return poses;
}

TEST(FindClosestIndex, FindsTheClosestAndBreaksTiesInVisitingOrderLikeTheScript) {
  const std::vector<double> three{0.0, 1.0, 2.0}, four{0.0, 1.0, 2.0, 3.0};
  EXPECT_EQ(findClosestIndex(three, 1.0), 1u);
  EXPECT_EQ(findClosestIndex(three, -5.0), 0u);
  EXPECT_EQ(findClosestIndex(three, 9.0), 2u);
  EXPECT_EQ(findClosestIndex(four, 2.4), 2u);
  EXPECT_EQ(findClosestIndex(four, 2.6), 3u);
  // Equidistant: the element probed first wins (the middle), so the tie goes left in one list, right in the other.
  EXPECT_EQ(findClosestIndex(three, 1.5), 1u);
  EXPECT_EQ(findClosestIndex(four, 1.5), 2u);
  EXPECT_EQ(findClosestIndex({7.0}, 100.0), 0u);
}

// Ground truth at 300 Hz contains every 30 Hz estimate stamp, so a perfect estimate compares equal poses.
TEST(Rpe, PerfectEstimateInAnotherWorldFrameHasZeroError) {
  const auto gt = path(300, 10, 0.5, 0.2);
  auto est = path(30, 10, 0.5, 0.2);
  const core::SE3 world_change = core::expSE3((core::Vector6d() << 3, -1, 2, 0.3, 1.2, -0.4).finished());
  for (auto& p : est) p.T_wc = world_change * p.T_wc;
  const RpeResult r = computeRpe(gt, est);
  // 301 estimated stamps; pairs (k, k+30) exist for k = 0..269 (from k = 270 on the closest stamp is the last).
  EXPECT_EQ(r.pairs.size(), 270u);
  EXPECT_LT(r.trans_m.max, 1e-9);
  EXPECT_LT(r.rot_deg.max, 1e-5);  // arccos near 1 resolves only ~2e-8 rad, in the script too
}

TEST(Rpe, ScaledTranslationGivesTheKnownDrift) {
  const auto gt = path(300, 10, 0.5, 0.0);
  auto est = path(30, 10, 0.5, 0.0);
  for (auto& p : est) p.T_wc.translation() *= 1.1;  // every metre becomes 1.1 m
  const RpeResult r = computeRpe(gt, est);
  ASSERT_EQ(r.pairs.size(), 270u);
  // The x motion over 1 s is 0.5 m, so the error is 0.05 m (plus a little from the sin(t) wobble in y).
  EXPECT_NEAR(r.trans_m.median, 0.05, 0.01);
  EXPECT_LT(r.rot_deg.max, 1e-9);
  for (const RpePair& pair : r.pairs) EXPECT_NEAR(pair.est_stamp_1 - pair.est_stamp_0, 1.0, 1e-6);

  RpeOptions undo;
  undo.scale = 1.0 / 1.1;  // the script's --scale undoes it
  EXPECT_LT(computeRpe(gt, est, undo).trans_m.max, 1e-9);
}

TEST(Rpe, SkipsPairsWithoutGroundTruthNearby) {
  auto gt = path(100, 10, 0.5, 0.2);
  std::vector<io::StampedPose> with_gap;
  for (const auto& p : gt) {
    if (p.timestamp < 1004.0 || p.timestamp > 1006.0) with_gap.push_back(p);
  }
  const auto est = path(30, 10, 0.5, 0.2);
  const RpeResult r = computeRpe(with_gap, est);
  EXPECT_LT(r.pairs.size(), 270u);
  EXPECT_GT(r.pairs.size(), 150u);
  for (const RpePair& pair : r.pairs) {
    // 2 x median gt interval = 0.02 s
    EXPECT_LE(std::abs(pair.gt_stamp_0 - pair.est_stamp_0), 0.02 + 1e-9);
    EXPECT_LE(std::abs(pair.gt_stamp_1 - pair.est_stamp_1), 0.02 + 1e-9);
  }
}

TEST(Rpe, SubsamplesDeterministicallyAboveMaxPairs) {
  const auto gt = path(300, 10, 0.5, 0.2);
  auto est = path(30, 10, 0.5, 0.2);
  for (std::size_t k = 0; k < est.size(); ++k) est[k].T_wc.translation().x() += 0.01 * std::sin(0.3 * k);
  RpeOptions options;
  options.max_pairs = 100;
  const RpeResult a = computeRpe(gt, est, options);
  const RpeResult b = computeRpe(gt, est, options);
  ASSERT_EQ(a.pairs.size(), 100u);
  for (std::size_t k = 0; k < a.pairs.size(); ++k) EXPECT_EQ(a.pairs[k].est_stamp_0, b.pairs[k].est_stamp_0);
  for (std::size_t k = 1; k < a.pairs.size(); ++k) EXPECT_LT(a.pairs[k - 1].est_stamp_0, a.pairs[k].est_stamp_0);
  options.seed = 1;
  const RpeResult c = computeRpe(gt, est, options);
  ASSERT_EQ(c.pairs.size(), 100u);
  bool differs = false;
  for (std::size_t k = 0; k < c.pairs.size(); ++k) differs |= c.pairs[k].est_stamp_0 != a.pairs[k].est_stamp_0;
  EXPECT_TRUE(differs);
  options.max_pairs = 0;  // 0 = all
  EXPECT_EQ(computeRpe(gt, est, options).pairs.size(), 270u);
}

TEST(Rpe, TooShortAnEstimateGivesNoPairsInsteadOfThrowing) {
  const auto gt = path(100, 10, 0.5, 0.2);
  const auto est = path(30, 0.5, 0.5, 0.2);  // shorter than delta
  const RpeResult r = computeRpe(gt, est);
  EXPECT_EQ(r.pairs.size(), 0u);
  EXPECT_TRUE(std::isnan(r.trans_m.rmse));
}

}  // namespace
}  // namespace amos::eval
