#include "amos/geometry/epnp.h"

#include <gtest/gtest.h>

#include <random>

namespace amos::geometry {
namespace {

struct Problem {
  std::vector<Eigen::Vector3d> points_w;
  std::vector<Eigen::Vector2d> normalized;
  core::SE3 T_cw;
};

// n points in front of the camera; `flat` squeezes them onto the world plane z = 2 (a wall).
Problem makeProblem(int n, unsigned seed, bool flat = false, double noise = 0.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> gauss(0.0, noise > 0 ? noise : 1.0);
  Problem p;
  core::Vector6d xi;
  xi << 0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng), 0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng);
  p.T_cw = core::expSE3(xi);
  const core::SE3 T_wc = p.T_cw.inverse();
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d p_c(u(rng), 0.75 * u(rng), 3.0 + u(rng));
    if (flat) {
      p_c = T_wc * p_c;
      p_c.z() = 2.0;  // world plane
      p_c = p.T_cw * p_c;
    }
    p.points_w.push_back(T_wc * p_c);
    Eigen::Vector2d xy = p_c.head<2>() / p_c.z();
    if (noise > 0) xy += Eigen::Vector2d(gauss(rng), gauss(rng));
    p.normalized.push_back(xy);
  }
  return p;
}

double translationError(const core::SE3& a, const core::SE3& b) { return core::translationNorm(a * b.inverse()); }
double rotationError(const core::SE3& a, const core::SE3& b) { return core::rotationAngle(a * b.inverse()); }

TEST(Epnp, ExactWithoutNoise) {
  for (int n : {5, 6, 10, 100}) {
    for (unsigned seed = 0; seed < 20; ++seed) {
      const Problem p = makeProblem(n, seed);
      const auto T = solveEpnp(p.points_w, p.normalized);
      ASSERT_TRUE(T) << "n " << n << " seed " << seed;
      EXPECT_LT(translationError(*T, p.T_cw), 1e-6) << "n " << n << " seed " << seed;
      EXPECT_LT(rotationError(*T, p.T_cw), 1e-6) << "n " << n << " seed " << seed;
    }
  }
}

TEST(Epnp, PlanarPoints) {
  for (int n : {5, 20}) {
    for (unsigned seed = 0; seed < 10; ++seed) {
      const Problem p = makeProblem(n, 100 + seed, true);
      const auto T = solveEpnp(p.points_w, p.normalized);
      ASSERT_TRUE(T) << "seed " << seed;
      EXPECT_LT(translationError(*T, p.T_cw), 1e-6) << "n " << n << " seed " << seed;
      EXPECT_LT(rotationError(*T, p.T_cw), 1e-6) << "n " << n << " seed " << seed;
    }
  }
}

TEST(Epnp, AccurateWithNoise) {
  // 0.5 px at f = 500 on 100 points 2..4 m away: a few millimetres.
  const Problem p = makeProblem(100, 7, false, 0.5 / 500.0);
  const auto T = solveEpnp(p.points_w, p.normalized);
  ASSERT_TRUE(T);
  EXPECT_LT(translationError(*T, p.T_cw), 0.02);
  EXPECT_LT(rotationError(*T, p.T_cw), 0.005);
}

TEST(Epnp, DegenerateInputs) {
  const Problem p = makeProblem(3, 1);
  EXPECT_FALSE(solveEpnp(p.points_w, p.normalized));  // fewer than 4 points
  std::vector<Eigen::Vector3d> same(6, Eigen::Vector3d(0, 0, 3));
  std::vector<Eigen::Vector2d> xy(6, Eigen::Vector2d(0, 0));
  EXPECT_FALSE(solveEpnp(same, xy));
  const Problem q = makeProblem(6, 2);
  EXPECT_FALSE(solveEpnp(q.points_w, std::vector<Eigen::Vector2d>(5)));  // size mismatch
}

}  // namespace
}  // namespace amos::geometry
