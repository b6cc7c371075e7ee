// Micro-benchmarks of the feature layer on a real TUM fr2/desk frame (640x480): ORB extraction at 1000
// features, brute-force Hamming matching of two frames' descriptors, keypoint-grid window queries, and
// PnP RANSAC. Single-threaded OpenCV, so the figures are per core.
//   bin/bench_features --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "amos/core/camera.h"
#include "amos/feature/keypoint_grid.h"
#include "amos/feature/orb_extractor.h"
#include "amos/geometry/pnp_ransac.h"
#include "amos/feature/descriptor_distance.h"

namespace {

using namespace amos;

// Grayscale frame `index` (sorted by name) of the TUM fr2/desk sample; empty when the data is missing.
cv::Mat tumFrame(size_t index) {
  const std::filesystem::path dir = std::filesystem::path(AMOS_SHARED_DIR) / "data/tum_fr2_desk_first50/rgb";
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (index >= files.size()) return {};
  return cv::imread(files[index].string(), cv::IMREAD_GRAYSCALE);
}

struct Frame {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

Frame extractFrame(size_t index, int features) {
  feature::OrbOptions options;
  options.num_features = features;
  Frame f;
  const cv::Mat gray = tumFrame(index);
  if (!gray.empty()) feature::OrbExtractor(options).extract(gray, f.keypoints, f.descriptors);
  return f;
}

void BM_OrbExtract(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat gray = tumFrame(0);
  if (gray.empty()) {
    state.SkipWithError("missing AMOS_SHARED_DIR/data/tum_fr2_desk_first50");
    return;
  }
  feature::OrbOptions options;
  options.num_features = static_cast<int>(state.range(0));
  const feature::OrbExtractor orb(options);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (auto _ : state) {
    orb.extract(gray, keypoints, descriptors);
    benchmark::DoNotOptimize(descriptors.data);
  }
  state.counters["keypoints"] = static_cast<double>(keypoints.size());
}
BENCHMARK(BM_OrbExtract)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);

void BM_HammingBruteForce(benchmark::State& state) {
  const Frame a = extractFrame(0, 1000), b = extractFrame(1, 1000);
  if (a.keypoints.empty() || b.keypoints.empty()) {
    state.SkipWithError("missing AMOS_SHARED_DIR/data/tum_fr2_desk_first50");
    return;
  }
  size_t matches = 0;
  for (auto _ : state) {
    const auto m = feature::matchBruteForce(a.descriptors, b.descriptors, feature::kDescriptorDistanceLow, 0.8f);
    matches = m.size();
    benchmark::DoNotOptimize(m.data());
  }
  state.counters["matches"] = static_cast<double>(matches);
  state.counters["pairs"] = static_cast<double>(a.descriptors.rows) * b.descriptors.rows;
}
BENCHMARK(BM_HammingBruteForce)->Unit(benchmark::kMillisecond);

void BM_KeypointGridBuild(benchmark::State& state) {
  const Frame f = extractFrame(0, 1000);
  for (auto _ : state) {
    feature::KeypointGrid grid(cv::Rect2d(0, 0, 640, 480), f.keypoints);
    benchmark::DoNotOptimize(grid.size());
  }
}
BENCHMARK(BM_KeypointGridBuild)->Unit(benchmark::kMicrosecond);

// One query per iteration, at random positions, with the window radius as argument (pixels).
void BM_KeypointGridQuery(benchmark::State& state) {
  const Frame f = extractFrame(0, 1000);
  if (f.keypoints.empty()) {
    state.SkipWithError("missing AMOS_SHARED_DIR/data/tum_fr2_desk_first50");
    return;
  }
  const feature::KeypointGrid grid(cv::Rect2d(0, 0, 640, 480), f.keypoints);
  std::mt19937 rng(1);
  std::vector<cv::Point2d> queries(1024);
  for (auto& q : queries) q = {static_cast<double>(rng() % 640), static_cast<double>(rng() % 480)};
  const double radius = static_cast<double>(state.range(0));
  std::vector<int> found;
  size_t k = 0, total = 0;
  for (auto _ : state) {
    const cv::Point2d& q = queries[k++ & 1023];
    grid.featuresInArea(q.x, q.y, radius, -1, -1, found);
    total += found.size();
    benchmark::DoNotOptimize(found.data());
  }
  state.counters["found_per_query"] = static_cast<double>(total) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_KeypointGridQuery)->Arg(15)->Arg(50)->Unit(benchmark::kNanosecond);

// 500 correspondences, 30% outliers, 1 px noise: the size of a tracking-time PnP problem.
void BM_PnpRansac(benchmark::State& state) {
  core::CameraIntrinsics k;
  k.fx = 520.9;
  k.fy = 521.0;
  k.cx = 325.1;
  k.cy = 249.7;
  const core::PinholeCamera camera(k);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> noise(0, 1);
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d p = camera.backProject(640 * u01(rng), 480 * u01(rng), 1 + 3 * u01(rng));
    points.push_back(p);
    pixels.push_back(u01(rng) < 0.3 ? Eigen::Vector2d(640 * u01(rng), 480 * u01(rng))
                                    : Eigen::Vector2d(camera.project(p) + Eigen::Vector2d(noise(rng), noise(rng))));
  }
  geometry::PnpRansacOptions options;
  size_t inliers = 0;
  for (auto _ : state) {
    const auto r = geometry::solvePnpRansac(points, pixels, camera, options);
    inliers = r.inliers.size();
  }
  state.counters["inliers"] = static_cast<double>(inliers);
}
BENCHMARK(BM_PnpRansac)->Unit(benchmark::kMillisecond);

}  // namespace
