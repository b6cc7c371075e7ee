#include "amos/loop/pose_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "amos/core/error.h"

namespace amos::loop {
namespace {

// Camera centres on a circle of radius 2 m, looking outwards, one vertex every 10 degrees (36 poses).
std::vector<core::SE3> circle() {
  std::vector<core::SE3> T_iw;
  for (int k = 0; k < 36; ++k) {
    const double a = k * M_PI / 18;
    core::Vector6d xi;
    xi << 0, 0, 0, 0, a, 0;
    core::SE3 T_wc = core::expSE3(xi);
    T_wc.translation() = Eigen::Vector3d(2 * std::sin(a), 0.1 * std::sin(3 * a), 2 * std::cos(a));
    T_iw.push_back(T_wc.inverse());
  }
  return T_iw;
}

double meanPositionError(const std::vector<core::SE3>& a, const std::vector<core::SE3>& b) {
  double sum = 0;
  for (std::size_t k = 0; k < a.size(); ++k) sum += (a[k].inverse().translation() - b[k].inverse().translation()).norm();
  return sum / static_cast<double>(a.size());
}

TEST(PoseGraph, LoopEdgeRemovesAccumulatedDrift) {
  const std::vector<core::SE3> truth = circle();
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 1);
  // Odometry edges with a small biased error each (drift), and one exact loop edge 35 -> 0.
  std::vector<PoseGraphEdge> edges;
  std::vector<core::SE3> drifted{truth[0]};
  for (int k = 1; k < 36; ++k) {
    core::Vector6d e;
    e << 0.004 + 0.001 * n(rng), 0.001 * n(rng), 0.001 * n(rng), 0.0005 * n(rng), 0.002 + 0.0005 * n(rng), 0;
    const core::SE3 T_prev_k = core::expSE3(e) * truth[k - 1] * truth[k].inverse();  // measured T_(k-1),k
    edges.push_back({k - 1, k, T_prev_k, 1.0});
    drifted.push_back(T_prev_k.inverse() * drifted.back());
  }
  edges.push_back({35, 0, truth[35] * truth[0].inverse(), 1.0});
  std::vector<bool> fixed(36, false);
  fixed[0] = true;
  const double before = meanPositionError(drifted, truth);
  const PoseGraphResult r = optimizePoseGraph(drifted, fixed, edges, PoseGraphOptions{});
  const double after = meanPositionError(r.T_iw, truth);
  EXPECT_GT(before, 0.05);
  // Biased odometry cannot be undone exactly; spreading the loop error along the chain must still halve it.
  EXPECT_LT(after, 0.5 * before);
  // The loop itself closes: the end relative to the start now agrees with the loop measurement.
  const core::SE3 gap_before = (truth[35] * truth[0].inverse()).inverse() * drifted[35] * drifted[0].inverse();
  const core::SE3 gap_after = (truth[35] * truth[0].inverse()).inverse() * r.T_iw[35] * r.T_iw[0].inverse();
  EXPECT_LT(core::translationNorm(gap_after), 0.1 * core::translationNorm(gap_before));
  EXPECT_LT(r.final_cost, r.initial_cost);
  EXPECT_TRUE(r.T_iw[0].isApprox(drifted[0]));  // the fixed vertex stays put
}

TEST(PoseGraph, ConsistentEdgesKeepTheirPoses) {
  const std::vector<core::SE3> truth = circle();
  std::vector<PoseGraphEdge> edges;
  for (int k = 1; k < 36; ++k) edges.push_back({k - 1, k, truth[k - 1] * truth[k].inverse(), 1.0});
  std::vector<bool> fixed(36, false);
  fixed[0] = true;
  const PoseGraphResult r = optimizePoseGraph(truth, fixed, edges, PoseGraphOptions{});
  EXPECT_LT(meanPositionError(r.T_iw, truth), 1e-9);
}

TEST(PoseGraph, RejectsAGraphWithoutAFixedVertex) {
  const std::vector<core::SE3> truth = circle();
  EXPECT_THROW(optimizePoseGraph(truth, std::vector<bool>(36, false), {}, PoseGraphOptions{}), core::Error);
}

}  // namespace
}  // namespace amos::loop
