// SLAM core micro-benchmarks: local bundle adjustment (Ceres) and pose-only optimisation on synthetic scenes of
// the size ORB-SLAM2-style RGB-D mapping produces (10 keyframes, 1500 points, ~5 views each, 70% with depth).
#include <benchmark/benchmark.h>

#include <random>

#include "amos/geometry/pose_optimizer.h"
#include "amos/mapping/bundle_adjustment.h"

namespace {

using amos::core::SE3;
using amos::core::Vector6d;

amos::geometry::StereoProjection projection() { return {520.9, 521.0, 325.1, 249.7, 40.0}; }

amos::mapping::BaProblem makeLocalBaProblem(int num_keyframes, int num_points, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-1.5, 1.5), uy(-1.0, 1.0), uz(1.0, 4.0), unit(0, 1);
  std::normal_distribution<double> noise(0, 0.7), n01(0, 1);
  amos::mapping::BaProblem p;
  p.projection = projection();
  std::vector<SE3> truth;
  for (int k = 0; k < num_keyframes; ++k) {
    Vector6d xi;
    xi << -0.05 * k, 0.01 * k, 0.02 * k, 0.005 * k, 0.02 * k, 0.0;
    truth.push_back(amos::core::expSE3(xi));
    Vector6d d;
    d << 0.01 * n01(rng), 0.01 * n01(rng), 0.01 * n01(rng), 0.005 * n01(rng), 0.005 * n01(rng), 0.005 * n01(rng);
    p.keyframes.push_back({k == 0 ? truth[k] : amos::core::expSE3(d) * truth[k], k < 2});
  }
  for (int i = 0; i < num_points; ++i) {
    const Eigen::Vector3d x(ux(rng), uy(rng), uz(rng));
    p.points.push_back({x + 0.02 * Eigen::Vector3d(n01(rng), n01(rng), n01(rng))});
    const int first = static_cast<int>(unit(rng) * (num_keyframes - 4));
    for (int k = first; k < first + 5 && k < num_keyframes; ++k) {
      const Eigen::Vector3d pc = truth[k] * x;
      if (pc.z() <= 0.1) continue;
      amos::mapping::BaObservation o;
      o.keyframe = k;
      o.point = i;
      const double u = p.projection.fx * pc.x() / pc.z() + p.projection.cx;
      const double v = p.projection.fy * pc.y() / pc.z() + p.projection.cy;
      o.pixel = {u + noise(rng), v + noise(rng)};
      if (unit(rng) < 0.7) o.u_right = u - p.projection.bf / pc.z() + noise(rng);
      if (unit(rng) < 0.05) o.pixel += Eigen::Vector2d(30, -25);  // outliers
      p.observations.push_back(o);
    }
  }
  return p;
}

void BM_LocalBundleAdjustment(benchmark::State& state) {
  const auto problem = makeLocalBaProblem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), 7);
  amos::mapping::BundleAdjustmentOptions options;
  for (auto _ : state) {
    auto result = amos::mapping::solveBundleAdjustment(problem, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["observations"] = static_cast<double>(problem.observations.size());
}
BENCHMARK(BM_LocalBundleAdjustment)->Args({10, 1500})->Args({20, 3000})->Unit(benchmark::kMillisecond);

void BM_PoseOptimization(benchmark::State& state) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(-1.5, 1.5), uz(1.0, 4.0), unit(0, 1);
  std::normal_distribution<double> noise(0, 0.7);
  const auto proj = projection();
  std::vector<amos::geometry::PoseObservation> obs;
  for (int i = 0; i < state.range(0); ++i) {
    const Eigen::Vector3d pc(ux(rng), ux(rng) * 0.7, uz(rng));
    amos::geometry::PoseObservation o;
    o.point_w = pc;
    o.pixel = {proj.fx * pc.x() / pc.z() + proj.cx + noise(rng), proj.fy * pc.y() / pc.z() + proj.cy + noise(rng)};
    if (unit(rng) < 0.7) o.u_right = o.pixel.x() - proj.bf / pc.z();
    if (unit(rng) < 0.1) o.pixel += Eigen::Vector2d(40, 10);
    obs.push_back(o);
  }
  Vector6d d;
  d << 0.02, -0.01, 0.01, 0.01, 0.005, -0.01;
  const SE3 start = amos::core::expSE3(d);
  for (auto _ : state) {
    auto result = amos::geometry::optimizePose(obs, start, proj, amos::geometry::PoseOptimizerOptions{});
    benchmark::DoNotOptimize(result);
  }
}
BENCHMARK(BM_PoseOptimization)->Arg(300)->Arg(600)->Unit(benchmark::kMicrosecond);

}  // namespace
