// Micro-benchmarks of the photometric pose refinement (issue 42) on two real Bonn crowd frames (640x480, raw pixels
// with the camera's distortion, sampled through the lens model): the per-frame image preparation (mask, pyramid), a
// keyframe's template, and the joint refinement with 400 feature terms. Single-threaded OpenCV, so the figures are
// per core.
//   bin/bench_photometric --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "amos/core/camera.h"
#include "amos/geometry/photometric_alignment.h"

namespace {

using namespace amos;

const std::filesystem::path kDir = std::filesystem::path(AMOS_SHARED_DIR) / "data/bonn_crowd_dev";

// Grey image and depth (metres) of association line `index`; empty when the data is missing.
void bonnFrame(int index, cv::Mat& gray, cv::Mat& depth) {
  std::ifstream in(kDir / "associations.txt");
  std::string line;
  for (int i = 0; i <= index && std::getline(in, line); ++i) {
  }
  std::istringstream fields(line);
  std::string t_rgb, rgb, t_depth, depth_file;
  if (!(fields >> t_rgb >> rgb >> t_depth >> depth_file)) return;
  gray = cv::imread((kDir / rgb).string(), cv::IMREAD_GRAYSCALE);
  const cv::Mat raw = cv::imread((kDir / depth_file).string(), cv::IMREAD_UNCHANGED);
  if (!raw.empty()) raw.convertTo(depth, CV_32F, 1.0 / 5000);
}

core::PinholeCamera bonnCamera() {  // configs/bonn.yaml
  core::CameraIntrinsics in;
  in.fx = 542.822841;
  in.fy = 542.576870;
  in.cx = 315.593520;
  in.cy = 237.756098;
  in.k1 = 0.039903;
  in.k2 = -0.099343;
  in.p1 = -0.000730;
  in.p2 = -0.000144;
  return core::PinholeCamera(in);
}

struct Fixture {
  core::PinholeCamera camera = bonnCamera();
  geometry::StereoProjection projection{camera.fx(), camera.fy(), camera.cx(), camera.cy(), camera.fx() * 0.08};
  geometry::PhotometricOptions options;
  cv::Mat gray_r, depth_r, gray_c, depth_c, mask;
  bool ok = false;

  Fixture() {
    cv::setNumThreads(1);
    bonnFrame(0, gray_r, depth_r);
    bonnFrame(2, gray_c, depth_c);
    ok = !gray_r.empty() && !depth_r.empty() && !gray_c.empty();
    if (!ok) return;
    mask = cv::Mat::zeros(gray_c.size(), CV_8U);
    mask(cv::Rect(400, 100, 120, 300)).setTo(255);  // a person-sized dynamic region
  }
  geometry::PhotometricImage image(const cv::Mat& gray) const {
    return geometry::makePhotometricImage(gray, mask, projection, camera.intrinsics().lens(), options);
  }
};

void BM_PhotometricImage(benchmark::State& state) {
  const Fixture f;
  if (!f.ok) return state.SkipWithError("missing AMOS_SHARED_DIR/data/bonn_crowd_dev");
  for (auto _ : state) benchmark::DoNotOptimize(f.image(f.gray_c));
}
BENCHMARK(BM_PhotometricImage)->Unit(benchmark::kMicrosecond);

// The same into buffers kept from the frame before, as tracking::PhotometricRefiner does.
void BM_PhotometricImageReused(benchmark::State& state) {
  const Fixture f;
  if (!f.ok) return state.SkipWithError("missing AMOS_SHARED_DIR/data/bonn_crowd_dev");
  geometry::PhotometricImage image;
  for (auto _ : state) {
    geometry::makePhotometricImage(f.gray_c, f.mask, f.projection, f.camera.intrinsics().lens(), f.options, image);
    benchmark::DoNotOptimize(image.gray.front().data);
  }
}
BENCHMARK(BM_PhotometricImageReused)->Unit(benchmark::kMicrosecond);

void BM_PhotometricTemplate(benchmark::State& state) {
  const Fixture f;
  if (!f.ok) return state.SkipWithError("missing AMOS_SHARED_DIR/data/bonn_crowd_dev");
  const geometry::PhotometricImage image = f.image(f.gray_r);
  for (auto _ : state) benchmark::DoNotOptimize(geometry::makePhotometricTemplate(image, f.depth_r, f.options));
}
BENCHMARK(BM_PhotometricTemplate)->Unit(benchmark::kMicrosecond);

// 400 feature terms made from the template's level-0 points (stereo, as RGB-D keypoints are).
std::vector<geometry::PoseObservation> featuresOf(const geometry::PhotometricTemplate& t,
                                                  const geometry::StereoProjection& k) {
  std::vector<geometry::PoseObservation> out;
  const auto& points = t.levels.front();
  for (std::size_t i = 0; i < points.size() && out.size() < 400; i += 5) {
    const Eigen::Vector3d& p = points[i].p_r;
    geometry::PoseObservation o;
    o.point_w = p;
    o.pixel = {k.fx * p.x() / p.z() + k.cx + 0.3, k.fy * p.y() / p.z() + k.cy - 0.2};
    o.u_right = o.pixel.x() - k.bf / p.z();
    out.push_back(o);
  }
  return out;
}

void BM_PhotometricRefine(benchmark::State& state) {
  const Fixture f;
  if (!f.ok) return state.SkipWithError("missing AMOS_SHARED_DIR/data/bonn_crowd_dev");
  const geometry::PhotometricTemplate reference =
      geometry::makePhotometricTemplate(f.image(f.gray_r), f.depth_r, f.options);
  const geometry::PhotometricImage current = f.image(f.gray_c);
  const std::vector<geometry::PoseObservation> features = featuresOf(reference, f.projection);
  geometry::PhotometricProblem problem;
  problem.features = &features;
  problem.projection = f.projection;
  problem.reference = &reference;
  problem.current = &current;
  for (auto _ : state) {
    benchmark::DoNotOptimize(geometry::refinePosePhotometrically(problem, core::SE3::Identity(), f.options));
  }
}
BENCHMARK(BM_PhotometricRefine)->Unit(benchmark::kMicrosecond);

}  // namespace
