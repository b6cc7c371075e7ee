// Micro-benchmarks of the anti-dynamics front end (paper Section III) on two consecutive real frames of Bonn
// crowd (three people walking, moving camera) and on the synthetic depth-edge scene. OpenCV runs on one thread
// so the figures are single-core. Counters: superpixels, boundary recall of depth edges, tracks, clusters...
//   ./bin/bench_dynamic --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <map>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/config/slam_options.h"
#include "amos/dynamic/dynamic_front_end.h"
#include "amos/evidence/baseline_tracks.h"
#include "amos/evidence/depth_evidence.h"
#include "amos/evidence/evidence_sources.h"
#include "amos/evidence/rigid_movers.h"
#include "amos/segmentation/model_locator.h"
#include "amos/segmentation/segmenter_factory.h"
#include "amos/dynamic/superpixel_metrics.h"
#include "amos/eval/bonn_ground_truth.h"
#include "amos/eval/evaluate.h"
#include "amos/io/dataset.h"
#include "amos/run/sequence_run.h"

namespace {

using namespace amos;
using namespace amos::dynamic;
using namespace amos::evidence;

struct Frame {
  cv::Mat bgr, gray, depth;
};

struct BenchData {
  Frame last, current;
  core::PinholeCamera camera;
  cv::Mat depth_edges;  // reference edges of the current frame: depth steps > 0.1 m
  std::vector<PointTrack> tracks;
  core::SE3 T_cw_initial;
};

Frame loadFrame(const std::string& dir, const std::string& rgb, const std::string& depth) {
  Frame f;
  f.bgr = cv::imread(dir + rgb, cv::IMREAD_COLOR);
  const cv::Mat raw = cv::imread(dir + depth, cv::IMREAD_UNCHANGED);
  if (f.bgr.empty() || raw.type() != CV_16U) throw std::runtime_error("cannot read " + dir + rgb);
  raw.convertTo(f.depth, CV_32F, 1.0 / 5000.0);
  cv::cvtColor(f.bgr, f.gray, cv::COLOR_BGR2GRAY);
  return f;
}

// Frames 100 and 101 of the slice (people in view, camera moving).
const BenchData& data() {
  static const BenchData d = [] {
    cv::setNumThreads(1);
    const std::string dir = std::string(AMOS_SHARED_DIR) + "/data/bonn_crowd_dev/";
    std::ifstream assoc(dir + "associations.txt");
    std::vector<std::pair<std::string, std::string>> rows;
    std::string line;
    while (std::getline(assoc, line)) {
      std::istringstream s(line);
      std::string t1, rgb, t2, depth;
      if (s >> t1 >> rgb >> t2 >> depth) rows.emplace_back(rgb, depth);
    }
    if (rows.size() < 102) throw std::runtime_error("missing " + dir + "associations.txt");
    BenchData b;
    b.last = loadFrame(dir, rows[100].first, rows[100].second);
    b.current = loadFrame(dir, rows[101].first, rows[101].second);
    core::CameraIntrinsics intr;
    intr.fx = 542.822841, intr.fy = 542.576870, intr.cx = 315.593520, intr.cy = 237.756098;
    intr.k1 = 0.039903, intr.k2 = -0.099343, intr.p1 = -0.000730, intr.p2 = -0.000144;
    b.camera = core::PinholeCamera(intr);
    b.depth_edges = depthEdges(b.current.depth, 0.1);
    const DynamicOptions options;
    b.tracks = trackCorners(b.last.gray, b.current.gray, options.tracking);
    const auto points_w =
        backProjectTracks(b.tracks, b.last.depth, core::SE3::Identity(), b.camera, options.reprojection);
    b.T_cw_initial = estimateInitialPose({}, lastFrameCorrespondences(b.tracks, points_w, b.camera),
                                         core::SE3::Identity(), std::nullopt, b.camera, options.initial_pose)
                         .T_cw;
    return b;
  }();
  return d;
}

// Depth-SLIC on the real frame. Args: scale in percent, superpixel count, iterations.
void BM_DepthSlic(benchmark::State& state) {
  const BenchData& d = data();
  DepthSlicOptions options;
  options.scale = state.range(0) / 100.0;
  options.num_superpixels = static_cast<int>(state.range(1));
  options.iterations = static_cast<int>(state.range(2));
  SuperpixelSegmentation seg;
  for (auto _ : state) {
    seg = computeDepthSlic(d.current.bgr, d.current.depth, options);
    benchmark::DoNotOptimize(seg.labels.data);
  }
  state.counters["superpixels"] = static_cast<double>(seg.superpixels.size());
  state.counters["recall_2px"] = boundaryRecall(seg.labels, d.depth_edges, 2);
  state.counters["recall_4px"] = boundaryRecall(seg.labels, d.depth_edges, 4);
  DepthSlicOptions colour_only = options;
  colour_only.depth_scale_m = 1e9;
  state.counters["colour_only_recall_2px"] =
      boundaryRecall(computeDepthSlic(d.current.bgr, d.current.depth, colour_only).labels, d.depth_edges, 2);
}
// The assignment loop in 4 lanes (the x86-64 baseline) and in 8 (AVX2, chosen at run time): same labels.
void BM_DepthSlicLanes(benchmark::State& state) {
  const BenchData& d = data();
  const bool avx2 = state.range(0) != 0;
  for (auto _ : state) {
    const SuperpixelSegmentation seg = detail::computeDepthSlic(d.current.bgr, d.current.depth, DepthSlicOptions{}, avx2);
    benchmark::DoNotOptimize(seg.labels.data);
  }
}
BENCHMARK(BM_DepthSlicLanes)->ArgName("avx2")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_DepthSlic)
    ->Args({25, 300, 5})
    ->Args({50, 150, 5})
    ->Args({50, 300, 3})
    ->Args({50, 300, 4})
    ->Args({50, 300, 5})
    ->Args({50, 300, 10})
    ->Args({50, 600, 5})
    ->Args({100, 300, 5})
    ->Unit(benchmark::kMillisecond);

// Depth-SLIC on the synthetic scene of depth_slic_test: same grey texture everywhere, a disc 1.5 m in front of a
// wall at 3 m. Arg: 1 = with the depth term, 0 = colour only.
void BM_DepthSlicSyntheticDisc(benchmark::State& state) {
  cv::Mat bgr(480, 640, CV_8UC3);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> grey(90, 170);
  for (int by = 0; by < 480; by += 4)
    for (int bx = 0; bx < 640; bx += 4) {
      const int g = grey(rng);
      bgr(cv::Rect(bx, by, 4, 4)).setTo(cv::Scalar(g, g, g));
    }
  cv::Mat depth(480, 640, CV_32F, cv::Scalar(3.0f)), reference(480, 640, CV_32S, cv::Scalar(0));
  cv::circle(depth, {301, 237}, 113, cv::Scalar(1.5f), cv::FILLED);
  cv::circle(reference, {301, 237}, 113, cv::Scalar(1), cv::FILLED);
  DepthSlicOptions options;
  if (state.range(0) == 0) options.depth_scale_m = 1e9;
  SuperpixelSegmentation seg;
  for (auto _ : state) seg = computeDepthSlic(bgr, depth, options);
  state.counters["recall_2px"] = boundaryRecall(seg.labels, labelBoundaries(reference), 2);
  state.counters["leakage"] = leakage(seg.labels, reference);
}
BENCHMARK(BM_DepthSlicSyntheticDisc)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_KMeansClusters(benchmark::State& state) {
  const BenchData& d = data();
  SuperpixelSegmentation seg = computeDepthSlic(d.current.bgr, d.current.depth, DepthSlicOptions{});
  const ClusteringOptions options;
  cv::Mat map;
  for (auto _ : state) {
    map = clusterSuperpixels(seg, options);
    benchmark::DoNotOptimize(map.data);
  }
  state.counters["superpixels"] = static_cast<double>(seg.superpixels.size());
  state.counters["clusters"] = clusterCount(seg);
}
BENCHMARK(BM_KMeansClusters)->Unit(benchmark::kMillisecond);

// The depth evidence (depth_evidence.h) of one Bonn frame pair against its superpixels, as the front end runs it
// once per comparison (the last frame; the baseline frame adds a second run), with the initial pose.
void BM_DepthEvidence(benchmark::State& state) {
  const BenchData& d = data();
  const SuperpixelSegmentation seg = computeDepthSlic(d.current.bgr, d.current.depth, DepthSlicOptions{});
  DepthEvidenceOptions options;
  const DepthSampleGrid grid(d.camera, options.sample_step_px);
  const core::SE3 identity = core::SE3::Identity();
  DepthEvidence e;
  for (auto _ : state) {
    e = superpixelDepthEvidence({d.current.depth, d.T_cw_initial}, {d.last.depth, identity}, grid,
                                {seg.labels, static_cast<int>(seg.superpixels.size())}, {d.camera, 0.05, options});
    benchmark::DoNotOptimize(e.samples);
  }
  state.counters["samples"] = e.samples;
  state.counters["moving_superpixels"] = e.moving_superpixels;
}
BENCHMARK(BM_DepthEvidence)->Unit(benchmark::kMillisecond);

// The long-baseline tracks (baseline_tracks.h) of one Bonn frame's tracked points, as the front end runs them with
// Dynamic.BaselineTracks.enabled (both pyramids built inside, as there), here against the last frame, whose pose
// (identity) is known: the frame 10 back would cost the same.
void BM_BaselineTracks(benchmark::State& state) {
  const BenchData& d = data();
  const DynamicOptions options;
  const core::SE3 identity = core::SE3::Identity();
  std::vector<cv::Point2f> points;
  for (const PointTrack& t : d.tracks) points.push_back(t.current);
  BaselineMotion m;
  for (auto _ : state) {
    const BaselineImages frames{d.current.gray, d.current.depth, d.T_cw_initial, d.last.gray, identity};
    m = baselineMotion(points, frames, d.camera, options);
    benchmark::DoNotOptimize(m.moving_points);
  }
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["followed"] = static_cast<double>(m.points.size());
}
BENCHMARK(BM_BaselineTracks)->Unit(benchmark::kMillisecond);

// The rigid movers (rigid_movers.h) on a Bonn frame, as the front end runs them after the long-baseline tracks with
// Dynamic.RigidMovers.enabled. The baseline frame is the frame itself with a 240 x 200 px block moved 6 px to the
// left (what a slow mover does over ten frames), so that the fit and the sample test have a mover to work on.
struct RigidMoverFrame {
  cv::Mat baseline_gray;
  BaselineMotion motion;
  SuperpixelSegmentation segmentation;
  int count = 0;
};

RigidMoverFrame rigidMoverFrame(const BenchData& d, const DynamicOptions& options) {
  RigidMoverFrame f;
  const cv::Rect block(200, 140, 240, 200);
  f.baseline_gray = d.current.gray.clone();
  d.current.gray(block).copyTo(f.baseline_gray(block - cv::Point(6, 0)));
  std::vector<cv::Point2f> points;
  for (const PointTrack& t : d.tracks) points.push_back(t.current);
  const BaselineImages frames{d.current.gray, d.current.depth, d.T_cw_initial, f.baseline_gray, d.T_cw_initial};
  f.motion = baselineMotion(points, frames, d.camera, options);
  f.segmentation = computeDepthSlic(d.current.bgr, d.current.depth, DepthSlicOptions{});
  f.count = static_cast<int>(f.segmentation.superpixels.size());
  return f;
}

RigidMoverVerdict rigidMovers(const BenchData& d, const RigidMoverFrame& f, const DynamicOptions& options) {
  const RigidMoverFrames frames{
      d.camera, {d.current.gray, d.current.depth, d.T_cw_initial}, {f.baseline_gray, d.current.depth, d.T_cw_initial}};
  return rigidMoverSuperpixels(f.motion, frames, {f.segmentation.labels, f.count}, options.reprojection,
                               options.rigid_movers);
}

void BM_RigidMovers(benchmark::State& state) {
  const BenchData& d = data();
  const DynamicOptions options;
  const RigidMoverFrame f = rigidMoverFrame(d, options);
  RigidMoverVerdict v;
  for (auto _ : state) {
    v = rigidMovers(d, f, options);
    benchmark::DoNotOptimize(v.moving_superpixels);
  }
  state.counters["moving_points"] = f.motion.moving_points;
  state.counters["movers"] = static_cast<double>(v.movers.size());
  state.counters["votes"] = v.mover_votes + v.static_votes;
  state.counters["moving_superpixels"] = v.moving_superpixels;
}
BENCHMARK(BM_RigidMovers)->Unit(benchmark::kMillisecond);

void BM_CornerTracking(benchmark::State& state) {
  const BenchData& d = data();
  const CornerTrackingOptions options;
  std::vector<PointTrack> tracks;
  for (auto _ : state) tracks = trackCorners(d.last.gray, d.current.gray, options);
  state.counters["tracks"] = static_cast<double>(tracks.size());
}
BENCHMARK(BM_CornerTracking)->Unit(benchmark::kMillisecond);

// Corner detection alone on the real frame.
void BM_DetectCorners(benchmark::State& state) {
  const BenchData& d = data();
  const CornerTrackingOptions options;
  std::vector<cv::Point2f> corners;
  for (auto _ : state) corners = detectCorners(d.last.gray, options);
  state.counters["corners"] = static_cast<double>(corners.size());
}
BENCHMARK(BM_DetectCorners)->Unit(benchmark::kMillisecond);

// One frame pair's LK pyramids (both frames, with derivatives), the part of BM_CornerTracking that can be reused.
void BM_BuildPyramids(benchmark::State& state) {
  const BenchData& d = data();
  const CornerTrackingOptions options;
  for (auto _ : state) {
    const FramePairPyramids p = buildPyramids(d.last.gray, d.current.gray, options);
    benchmark::DoNotOptimize(p.last.data());
  }
}
BENCHMARK(BM_BuildPyramids)->Unit(benchmark::kMillisecond);

// Forward-backward LK of the last frame's corners on prebuilt pyramids. Args: LK window, maximum iterations,
// epsilon in 1/1000 px. Counters: tracks kept, and against the default settings (15, 30, 0.01 px): the tracks both
// keep, the median and the largest distance between their end points.
void BM_TrackPointsOnPyramids(benchmark::State& state) {
  const BenchData& d = data();
  CornerTrackingOptions options;
  options.lk_window = static_cast<int>(state.range(0));
  options.lk_max_iterations = static_cast<int>(state.range(1));
  options.lk_epsilon = static_cast<double>(state.range(2)) / 1000.0;
  std::vector<cv::Point2f> points;
  {
    cv::Mat small;
    cv::resize(d.last.gray, small, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    cv::goodFeaturesToTrack(small, points, 500, 0.01, 5.0);
    for (cv::Point2f& p : points) p = p * 2.f + cv::Point2f(0.5f, 0.5f);
  }
  const CornerTrackingOptions reference_options;
  const std::vector<PointTrack> reference =
      trackPoints(buildPyramids(d.last.gray, d.current.gray, reference_options), points, reference_options);
  const FramePairPyramids p = buildPyramids(d.last.gray, d.current.gray, options);
  std::vector<PointTrack> tracks;
  for (auto _ : state) tracks = trackPoints(p, points, options);
  std::map<int, cv::Point2f> end_of;
  for (const PointTrack& t : reference) end_of[t.source_index] = t.current;
  std::vector<double> differences;
  for (const PointTrack& t : tracks)
    if (const auto it = end_of.find(t.source_index); it != end_of.end()) differences.push_back(cv::norm(t.current - it->second));
  std::sort(differences.begin(), differences.end());
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["tracks"] = static_cast<double>(tracks.size());
  state.counters["common"] = static_cast<double>(differences.size());
  state.counters["median_diff_px"] = differences.empty() ? 0.0 : differences[differences.size() / 2];
  state.counters["max_diff_px"] = differences.empty() ? 0.0 : differences.back();
}
BENCHMARK(BM_TrackPointsOnPyramids)
    ->Args({15, 30, 10})
    ->Args({15, 10, 30})
    ->Args({13, 10, 30})
    ->Args({11, 10, 30})
    ->Args({11, 30, 10})
    ->Args({9, 10, 30})
    ->Unit(benchmark::kMillisecond);


// Eq. 5-6: back-projection, reprojection under the initial pose, per-cluster Cauchy means.
void BM_ReprojectionScoring(benchmark::State& state) {
  const BenchData& d = data();
  SuperpixelSegmentation seg = computeDepthSlic(d.current.bgr, d.current.depth, DepthSlicOptions{});
  const cv::Mat map = clusterSuperpixels(seg, ClusteringOptions{});
  const ReprojectionOptions options;
  std::vector<int> cluster_of_track;
  for (const PointTrack& t : d.tracks)
    cluster_of_track.push_back(map.at<int>(cvRound(t.current.y), cvRound(t.current.x)));
  std::vector<ClusterScore> scores;
  for (auto _ : state) {
    const auto points = backProjectTracks(d.tracks, d.last.depth, core::SE3::Identity(), d.camera, options);
    const auto errors = reprojectionErrors(d.tracks, points, d.T_cw_initial, d.camera);
    scores = scoreClusters(errors, cluster_of_track, clusterCount(seg), options);
  }
  int candidates = 0;
  for (const ClusterScore& s : scores) candidates += s.candidate;
  state.counters["tracks"] = static_cast<double>(d.tracks.size());
  state.counters["candidates"] = candidates;
}
BENCHMARK(BM_ReprojectionScoring)->Unit(benchmark::kMillisecond);

// Eq. 7-8: RANSAC + refit of F on all undistorted tracks, then every track's epipolar distance.
void BM_EpipolarJudgement(benchmark::State& state) {
  const BenchData& d = data();
  std::vector<cv::Point2f> a, b;
  for (const PointTrack& t : d.tracks) a.push_back(t.last), b.push_back(t.current);
  a = d.camera.undistort(a), b = d.camera.undistort(b);
  const EpipolarOptions options;
  FundamentalFit fit;
  int violators = 0;
  for (auto _ : state) {
    fit = fitFundamental(a, b, options);
    violators = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      violators += epipolarDistance(fit.F, {a[i].x, a[i].y}, {b[i].x, b[i].y}) > options.dynamic_threshold_px;
  }
  state.counters["f_inliers"] = fit.final_inliers;
  state.counters["violators"] = violators;
}
BENCHMARK(BM_EpipolarJudgement)->Unit(benchmark::kMillisecond);

void BM_InitialPoseLastFrameModel(benchmark::State& state) {
  const BenchData& d = data();
  const DynamicOptions options;
  InitialPoseResult r;
  for (auto _ : state) {
    const auto points_w =
        backProjectTracks(d.tracks, d.last.depth, core::SE3::Identity(), d.camera, options.reprojection);
    r = estimateInitialPose({}, lastFrameCorrespondences(d.tracks, points_w, d.camera), core::SE3::Identity(),
                            core::SE3::Identity(), d.camera, options.initial_pose);
  }
  state.counters["common_inliers"] = r.candidates[static_cast<int>(r.model)].common_inliers;
}
BENCHMARK(BM_InitialPoseLastFrameModel)->Unit(benchmark::kMillisecond);

// The whole geometric stage (mode geometry: superpixels, clusters, corner tracking, scoring, F, decision).
void BM_FrontEndGeometry(benchmark::State& state) {
  const BenchData& d = data();
  DynamicOptions options;
  options.mode = DynamicMode::kGeometry;
  const DynamicFrontEnd front_end(d.camera, options, makeEvidenceSources(d.camera, options));
  FrontEndInput in;
  in.gray = d.current.gray, in.bgr = d.current.bgr, in.depth = d.current.depth;
  in.last_gray = d.last.gray, in.last_depth = d.last.depth;
  in.T_cw_initial = d.T_cw_initial;
  FrontEndResult out;
  std::map<std::string, double> stage_ms;
  for (auto _ : state) {
    out = front_end.process(in);
    for (const auto& [stage, ms] : out.timings_ms) stage_ms[stage] += ms;
  }
  for (const auto& [stage, ms] : stage_ms) state.counters["ms_" + stage] = ms / state.iterations();
  state.counters["clusters"] = out.diagnostics.clusters;
  state.counters["candidates"] = out.diagnostics.candidate_clusters;
  state.counters["dynamic"] = out.diagnostics.dynamic_clusters;
  state.counters["dynamic_points"] = out.diagnostics.dynamic_points;
  state.counters["mask_share"] = static_cast<double>(cv::countNonZero(out.mask)) / out.mask.total();
}
BENCHMARK(BM_FrontEndGeometry)->Unit(benchmark::kMillisecond);

// The whole of `amos-slam run --mode full` on bonn_crowd_dev (configs/bonn.yaml), the loop of run::runSequence,
// with and without look-ahead (process(frame k, next = frame k+1): frame k+1 is segmented, and its features,
// pyramid, corners and superpixels are prepared, while frame k is tracked), and with settings changed from the
// file's: args {look_ahead 0/1, Segmentation.mask_input_size, Dynamic.LK.window, Dynamic.LK.maxIterations, LK
// epsilon in 1/1000 px, OpenCV threads (0 = OpenCV's default), System.deterministic 0/1, Segmentation.input_shape
// 0 = square / 1 = frame}. One iteration = one pass over
// the 270 frames. Counters: fps (wall), cpu_ms per frame (all threads of the
// process, from getrusage), ATE RMSE in metres, lost frames, and the median wait for the masks. Run it from the
// repository root (it reads configs/bonn.yaml):
//   ./build/bin/bench_dynamic --benchmark_filter=BonnFull --benchmark_repetitions=3
double processCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void BM_BonnFullSequence(benchmark::State& state) {
  const bool look_ahead = state.range(0) != 0;
  const std::string sequence = std::string(AMOS_SHARED_DIR) + "/data/bonn_crowd_dev";
  config::Settings settings = config::loadSettings("configs/bonn.yaml");
  settings.segmentation.mask_input_size = static_cast<int>(state.range(1));
  settings.dynamic.tracking.lk_window = static_cast<int>(state.range(2));
  settings.dynamic.tracking.lk_max_iterations = static_cast<int>(state.range(3));
  settings.dynamic.tracking.lk_epsilon = static_cast<double>(state.range(4)) / 1000.0;
  const int cv_threads = static_cast<int>(state.range(5));
  const bool deterministic = state.range(6) != 0;
  settings.segmentation.input_shape = state.range(7) == 0 ? "square" : "frame";
  const int default_threads = cv::getNumThreads();
  settings.segmentation.threads = cv_threads;  // applied by the segmenter; 0 leaves OpenCV's default
  double fps = 0, cpu_ms = 0, ate = 0, lost = 0, wait_ms = 0, keyframe_points_median = 0;
  std::map<std::string, double> stage_cpu_ms;  // median CPU per frame of the pipeline's cpu.* stages
  for (auto _ : state) {
    system::SlamSystem slam(config::slamOptionsFromSettings(settings, deterministic));
    dynamic::DynamicOptions options = settings.dynamic;
    options.mode = DynamicMode::kFull;
    segmentation::ModelSources sources;
    sources.environment = segmentation::processEnvironment();
    sources.default_dirs = std::vector<std::string>{"./models", std::string(AMOS_SHARED_DIR) + "/models"};
    auto worker = std::make_unique<segmentation::SegmentationWorker>(
        segmentation::createSegmenter(settings.segmentation, sources, segmentation::builtinSegmenterFactory()),
        settings.segmentation.dilation);
    system::DynamicPipeline pipeline(slam, options, std::move(worker));
    io::SequenceIndex index = io::indexSequence(sequence);
    const std::string gt_file = index.groundtruth_file;
    io::SequenceReader reader(std::move(index), settings.readerOptions());
    const double cpu_start = processCpuSeconds();
    core::Stopwatch wall;
    std::size_t frames = 0;
    std::vector<double> keyframe_points;
    // As runSequence does: with look-ahead the next frame's stage A runs while this one is in stage B.
    auto feed = [&] {
      if (auto f = reader.next()) pipeline.push(std::move(*f));
    };
    feed();
    while (pipeline.waiting() > 0) {
      if (look_ahead) feed();
      const system::ProcessedFrame out = pipeline.processNext();
      if (!look_ahead) feed();
      ++frames;
      const auto& view = *out.slam.view.reference_keyframe;
      keyframe_points.push_back(static_cast<double>(std::count(view.has_point.begin(), view.has_point.end(), true)));
    }
    keyframe_points_median = core::percentile(keyframe_points, 0.5);
    pipeline.finish();
    const double wall_s = wall.elapsedMs() / 1000.0;
    fps = static_cast<double>(frames) / wall_s;
    cpu_ms = 1000.0 * (processCpuSeconds() - cpu_start) / static_cast<double>(frames);
    lost = static_cast<double>(slam.stats().lost);
    const auto summary = pipeline.times().summary();
    if (const auto it = summary.find("dynamic.segmentation_wait"); it != summary.end()) wait_ms = it->second.median_ms;
    for (const auto& [stage, sum] : summary)
      if (stage.rfind("cpu.", 0) == 0) stage_cpu_ms[stage.substr(4)] = sum.median_ms;
    const auto gt = eval::bonnMarkerToCamera(io::readTumTrajectory(gt_file));
    ate = eval::evaluate(gt, slam.trajectory()).ate_rmse_m;
  }
  state.counters["fps"] = fps;
  state.counters["cpu_ms"] = cpu_ms;
  state.counters["ate_m"] = ate;
  state.counters["lost"] = lost;
  state.counters["segmentation_wait_ms"] = wait_ms;
  state.counters["keyframe_points"] = keyframe_points_median;  // points the reference-keyframe model tracks by LK
  for (const auto& [stage, ms] : stage_cpu_ms) state.counters["cpu_" + stage] = ms;
  cv::setNumThreads(default_threads);
}
BENCHMARK(BM_BonnFullSequence)
    ->Args({0, 256, 15, 30, 10, 0, 0, 0})  // the front end as it was: no look-ahead, export shapes, OpenCV threads
    ->Args({1, 160, 15, 30, 10, 1, 0, 0})  // defaults (with the look-ahead runSequence needs to pass)
    ->Args({0, 256, 15, 30, 10, 0, 1, 0})
    ->Args({1, 256, 15, 30, 10, 0, 1, 0})
    ->Args({1, 256, 15, 30, 10, 1, 1, 0})
    ->Args({1, 256, 15, 30, 10, 1, 1, 1})
    ->Args({1, 160, 15, 30, 10, 1, 1, 0})
    ->Args({1, 160, 15, 30, 10, 1, 1, 1})
    ->Args({1, 160, 11, 30, 10, 1, 0, 0})  // LK window 11 (proposed for configs/bonn.yaml)
    ->ArgNames({"look_ahead", "mask_input", "lk_window", "lk_iters", "lk_eps_milli", "cv_threads", "deterministic",
                "frame_shape"})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace
