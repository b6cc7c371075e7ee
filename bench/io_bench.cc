// Micro-benchmarks of PNG decoding on the first Bonn crowd frame (640x480): cv::imread (libpng + zlib) against
// io::readPng (libdeflate) for the 8-bit RGB image (IMREAD_COLOR) and the 16-bit depth image (IMREAD_UNCHANGED).
// File reading included, single-threaded; the label says the route readPng took ("decoded" = libdeflate).
//   bin/bench_io --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "amos/io/png_reader.h"

namespace {

using namespace amos;

// The first PNG (by name) of data/bonn_crowd_dev/<sub>; empty when the data is missing.
std::string bonnFile(const std::string& sub) {
  const std::filesystem::path dir = std::filesystem::path(AMOS_SHARED_DIR) / "data/bonn_crowd_dev" / sub;
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& entry : std::filesystem::directory_iterator(dir))
      if (entry.path().extension() == ".png") files.push_back(entry.path());
  if (files.empty()) return {};
  return std::min_element(files.begin(), files.end())->string();
}

const char* routeName(io::PngRoute route) {
  switch (route) {
    case io::PngRoute::decoded: return "decoded";
    case io::PngRoute::general: return "libpng";
    default: return "rejected";
  }
}

using Decoder = cv::Mat (*)(const std::string& file, int flags, io::PngReadInfo* info);

cv::Mat imreadFile(const std::string& file, int flags, io::PngReadInfo*) { return cv::imread(file, flags); }

void BM_DecodeBonn(benchmark::State& state, Decoder decode, const std::string& sub, int flags) {
  const std::string file = bonnFile(sub);
  if (file.empty()) {
    state.SkipWithError("missing AMOS_SHARED_DIR/data/bonn_crowd_dev");
    return;
  }
  io::PngReadInfo info;
  for (auto _ : state) {
    const cv::Mat image = decode(file, flags, &info);
    benchmark::DoNotOptimize(image.data);
  }
  if (decode == io::readPng) state.SetLabel(routeName(info.route));
}
BENCHMARK_CAPTURE(BM_DecodeBonn, imread_rgb, imreadFile, "rgb", cv::IMREAD_COLOR)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DecodeBonn, readPng_rgb, io::readPng, "rgb", cv::IMREAD_COLOR)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DecodeBonn, imread_depth, imreadFile, "depth", cv::IMREAD_UNCHANGED)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DecodeBonn, readPng_depth, io::readPng, "depth", cv::IMREAD_UNCHANGED)
    ->Unit(benchmark::kMillisecond);

}  // namespace
