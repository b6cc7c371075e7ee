// bench_segment: time per frame of the prior-dynamic-object segmenter (NanoDet-m + selfie masks, mask painting
// and 31x31 dilation included) on bonn_crowd_dev, at detector input 320 and 416 with 1 and 2 OpenCV threads, and
// the frame rate when segmentation runs in its worker thread overlapped with ORB extraction in the calling thread
// (the project's feature::OrbExtractor with its default OrbOptions: 1000 features, 8 levels, scale 1.2, as
// ORB-SLAM2's TUM settings), against doing both in turn.
//
// Each benchmark iteration is one frame; one repetition passes once over 30 frames spread over the sequence;
// ask for several repetitions and read the medians.
// Counters: median_ms / p95_ms = per-frame time within the repetition; fps = frames per second of wall time.
// Run e.g.: bench_segment --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <future>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "amos/core/stage_timer.h"
#include "amos/segmentation/segment_masks.h"
#include "amos/segmentation/segmentation_worker.h"
#include "amos/segmentation/segmenter_factory.h"
#include "amos/feature/orb_extractor.h"
#include "amos/io/dataset.h"

namespace {

using namespace amos;

constexpr std::size_t kFrames = 30;

struct BenchFrame {
  cv::Mat bgr, gray;
};

// 30 frames spread over bonn_crowd_dev, read once (immutable afterwards).
const std::vector<BenchFrame>& benchFrames() {
  static const std::vector<BenchFrame> frames = [] {
    const auto index = io::indexSequence(std::string(AMOS_SHARED_DIR) + "/data/bonn_crowd_dev");
    std::vector<BenchFrame> out;
    for (std::size_t k = 0; k < kFrames; ++k) {
      const auto& entry = index.frames[k * index.frames.size() / kFrames];
      BenchFrame f;
      f.bgr = cv::imread(entry.rgb_file, cv::IMREAD_COLOR);
      if (f.bgr.empty()) throw std::runtime_error("cannot read " + entry.rgb_file);
      cv::cvtColor(f.bgr, f.gray, cv::COLOR_BGR2GRAY);
      out.push_back(std::move(f));
    }
    return out;
  }();
  return frames;
}

std::unique_ptr<segmentation::Segmenter> makeSegmenter(segmentation::SegmenterOptions options) {
  segmentation::ModelSources sources;
  sources.environment = segmentation::processEnvironment();
  sources.default_dirs = {"./models", "../shared/models", std::string(AMOS_SHARED_DIR) + "/models"};
  return segmentation::createSegmenter(options, sources, segmentation::builtinSegmenterFactory());
}

std::unique_ptr<segmentation::Segmenter> makeSegmenter(int input_size, int threads) {
  segmentation::SegmenterOptions options;
  options.input_size = input_size;
  options.threads = threads;
  return makeSegmenter(options);
}

// The export's own shapes: square 320 detector input (letterboxed frame), person crops at 256x256.
segmentation::SegmenterOptions exportShapes() {
  segmentation::SegmenterOptions options;
  options.input_shape = "square";
  options.mask_input_size = 256;
  return options;
}

// Undilated masks of the bench frames with the export's shapes: the reference the cheaper shapes are compared to.
const std::vector<cv::Mat>& referenceMasks() {
  static const std::vector<cv::Mat> masks = [] {
    cv::setNumThreads(1);
    auto segmenter = makeSegmenter(exportShapes());
    std::vector<cv::Mat> out;
    for (const auto& frame : benchFrames()) {
      out.push_back(segmentation::segmentFrame(*segmenter, {}, 0, frame.bgr).mask);
    }
    return out;
  }();
  return masks;
}

feature::OrbExtractor makeOrb() { return feature::OrbExtractor(feature::OrbOptions{}); }

void setTimingCounters(benchmark::State& state, const std::vector<double>& frame_ms) {
  state.counters["median_ms"] = core::percentile(frame_ms, 0.5);
  state.counters["p95_ms"] = core::percentile(frame_ms, 0.95);
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Segmentation alone, synchronously: args {input size, OpenCV threads}.
void BM_Segment(benchmark::State& state) {
  const auto& frames = benchFrames();
  cv::setNumThreads(static_cast<int>(state.range(1)));
  auto segmenter = makeSegmenter(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const segmentation::MaskDilationOptions dilation;
  std::vector<double> frame_ms;
  std::size_t i = 0, instances = 0;
  for (auto _ : state) {
    core::Stopwatch watch;
    const auto result = segmentation::segmentFrame(*segmenter, dilation, i, frames[i % frames.size()].bgr);
    frame_ms.push_back(watch.elapsedMs());
    instances += result.instances.size();
    ++i;
  }
  setTimingCounters(state, frame_ms);
  state.counters["people_per_frame"] = static_cast<double>(instances) / static_cast<double>(i);
}

// Cost and agreement of cheaper network shapes, one OpenCV thread: args {detector input shape (0 = square 320,
// 1 = frame-shaped 320x256), mask network input side}. Counters: cpu_ms per frame (this thread), mean / min IoU of
// the undilated person masks against the export's shapes ({0, 256}) over the 30 frames.
void BM_SegmentShapes(benchmark::State& state) {
  const auto& frames = benchFrames();
  const auto& reference = referenceMasks();
  cv::setNumThreads(1);
  segmentation::SegmenterOptions options = exportShapes();
  options.input_shape = state.range(0) == 0 ? "square" : "frame";
  options.mask_input_size = static_cast<int>(state.range(1));
  auto segmenter = makeSegmenter(options);
  std::vector<double> frame_ms, iou(frames.size(), 1.0);
  std::size_t i = 0;
  const std::clock_t cpu_start = std::clock();
  for (auto _ : state) {
    core::Stopwatch watch;
    const std::size_t k = i % frames.size();
    const auto result = segmentation::segmentFrame(*segmenter, {}, i, frames[k].bgr);
    frame_ms.push_back(watch.elapsedMs());
    iou[k] = segmentation::maskIoU(result.mask, reference[k]);
    ++i;
  }
  const double cpu_ms = 1000.0 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  setTimingCounters(state, frame_ms);
  state.counters["cpu_ms"] = cpu_ms / static_cast<double>(i);
  double sum = 0, worst = 1;
  for (double v : iou) sum += v, worst = std::min(worst, v);
  state.counters["mean_iou"] = sum / static_cast<double>(iou.size());
  state.counters["min_iou"] = worst;
}

// Growing the person masks of the 30 frames by the default 31x31 ellipse: arg 0 = cv::dilate on the mask's
// neighbourhood (bounding box grown by the radius), 1 = dilateMask (row-run decomposition on the same
// neighbourhood, same result). One OpenCV thread.
void BM_DilateMask(benchmark::State& state) {
  const auto& masks = referenceMasks();
  cv::setNumThreads(1);
  const segmentation::MaskDilationOptions options;
  const cv::Mat kernel = segmentation::dilationKernel(options);
  std::size_t i = 0;
  for (auto _ : state) {
    const cv::Mat& mask = masks[i++ % masks.size()];
    cv::Mat grown;
    if (state.range(0) == 0) {
      grown = cv::Mat::zeros(mask.size(), CV_8UC1);
      const cv::Rect box = cv::boundingRect(mask);
      const cv::Rect roi = cv::Rect(box.x - 15, box.y - 15, box.width + 30, box.height + 30) &
                           cv::Rect(0, 0, mask.cols, mask.rows);
      cv::Mat target = grown(roi);
      if (!box.empty())
        cv::dilate(mask(roi), target, kernel, cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    } else {
      grown = segmentation::dilateMask(mask, options);
    }
    benchmark::DoNotOptimize(grown.data);
  }
}
BENCHMARK(BM_DilateMask)->Arg(0)->Arg(1)->ArgName("row_runs")->Unit(benchmark::kMillisecond);

// ORB extraction alone: arg {OpenCV threads}.
void BM_OrbExtractor(benchmark::State& state) {
  const auto& frames = benchFrames();
  cv::setNumThreads(static_cast<int>(state.range(0)));
  const auto orb = makeOrb();
  std::vector<double> frame_ms;
  std::size_t i = 0;
  for (auto _ : state) {
    core::Stopwatch watch;
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb.extract(frames[i % frames.size()].gray, keypoints, descriptors);
    frame_ms.push_back(watch.elapsedMs());
    benchmark::DoNotOptimize(descriptors.data);
    ++i;
  }
  setTimingCounters(state, frame_ms);
}

// Segmentation then ORB in the same thread (the frame time if nothing were overlapped).
void BM_SegmentThenOrb(benchmark::State& state) {
  const auto& frames = benchFrames();
  cv::setNumThreads(static_cast<int>(state.range(1)));
  auto segmenter = makeSegmenter(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto orb = makeOrb();
  const segmentation::MaskDilationOptions dilation;
  std::vector<double> frame_ms;
  std::size_t i = 0;
  for (auto _ : state) {
    core::Stopwatch watch;
    const auto& frame = frames[i % frames.size()];
    const auto result = segmentation::segmentFrame(*segmenter, dilation, i, frame.bgr);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb.extract(frame.gray, keypoints, descriptors);
    benchmark::DoNotOptimize(result.dilated_mask.data);
    frame_ms.push_back(watch.elapsedMs());
    ++i;
  }
  setTimingCounters(state, frame_ms);
}

// What the SLAM thread does: submit frame i to the segmentation worker, extract ORB features of frame i while it
// is segmented, then wait for frame i's masks. args {input size, OpenCV threads}.
void BM_SegmentOverlappedWithOrb(benchmark::State& state) {
  const auto& frames = benchFrames();
  cv::setNumThreads(static_cast<int>(state.range(1)));
  segmentation::SegmentationWorker worker(
      makeSegmenter(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))), {}, 2);
  const auto orb = makeOrb();
  std::vector<double> frame_ms;
  std::size_t i = 0;
  for (auto _ : state) {
    core::Stopwatch watch;
    const auto& frame = frames[i % frames.size()];
    auto pending = worker.submit(i, frame.bgr);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb.extract(frame.gray, keypoints, descriptors);
    const auto result = pending.get();
    benchmark::DoNotOptimize(result.dilated_mask.data);
    frame_ms.push_back(watch.elapsedMs());
    ++i;
  }
  setTimingCounters(state, frame_ms);
}

void sizesAndThreads(benchmark::internal::Benchmark* b) {
  for (int size : {320, 416})
    for (int threads : {1, 2}) b->Args({size, threads});
  b->ArgNames({"input", "threads"})->Iterations(kFrames)->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Segment)->Apply(sizesAndThreads);
BENCHMARK(BM_SegmentShapes)
    ->ArgsProduct({{0, 1}, {256, 192, 160, 128}})
    ->ArgNames({"frame_shape", "mask_input"})
    ->Iterations(kFrames)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OrbExtractor)->Arg(1)->Arg(2)->ArgName("threads")->Iterations(kFrames)->UseRealTime()->Unit(
    benchmark::kMillisecond);
BENCHMARK(BM_SegmentThenOrb)->Apply(sizesAndThreads);
BENCHMARK(BM_SegmentOverlappedWithOrb)->Apply(sizesAndThreads);

}  // namespace
