// amos-slam run: SLAM over one RGB-D sequence, read as fast as possible, replayed at its recorded rate
// (--realtime) or live from a camera (--camera openni2[:URI]; Ctrl-C ends the session), optionally recorded
// (--record DIR). Writes trajectory.txt, keyframes.txt, map.ply, stats.json and settings_used.yaml (the settings
// it ran with) into --output (with --save-masks also masks/ and overlays/), trajectory_live.txt and frames.tsv
// frame by frame as it goes (a killed run leaves them), and run_manifest.json (what it writes there, for
// --overwrite); the folder is locked for the run (report/output_folder.h). Prints where the frames came from
// (delivered / processed / dropped, latency), ATE / RPE when the sequence has ground truth and the dynamic mask's
// pixel precision / recall / IoU when it has ground-truth mover masks. With the viewer module it also writes
// report.html, and --viewer serves a live view of the run (run_watchers.h). All work is in amos::run /
// amos::report / amos::config / amos::system / amos::viewer.
// Streams: progress and warnings on stderr, the summary on stdout. Exit status: 0, 1 for an error (before the run,
// or one that ended it: the outputs of the frames processed are written first), 130 / 143 when SIGINT / SIGTERM
// ended it (outputs written likewise).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <semaphore.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <tuple>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "amos/config/settings.h"
#include "amos/run/settings_sections.h"
#include "amos/config/settings_writer.h"
#ifdef AMOS_HAVE_DENSE_PLUGIN
#include "amos/run/dense_plugin_loader.h"
#endif
#include "amos/eval/jitter.h"
#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/core/stop_request.h"
#include "amos/report/output_folder.h"
#include "amos/report/run_report.h"
#include "amos/run/bag_source.h"
#include "amos/run/sequence_run.h"
#include "commands.h"
#include "run_watchers.h"

namespace amos::app {
namespace {

struct RunArgs {
  std::string sequence, config, output, mode = "full", models, camera, record;
  bool deterministic = false, save_masks = false, realtime = false, overwrite = false, strict = false;
  bool dense = false;             // --dense
  bool fail_on_optional = false;  // --fail-on-optional
  std::size_t max_frames = 0, overlays = 8, progress_every = 100;
  std::size_t first_frame = 0;
  std::string load_map, save_map;  // --load-map / --save-map
  bool localize = false;
  std::string rgb_topic, depth_topic, camera_info_topic;  // --sequence X.bag
  std::string groundtruth_topic, groundtruth_parent_frame = "/world", groundtruth_child_frame = "/kinect";
  ViewerArgs viewer;
};

// The command line's choices as report.html lists them.
std::string runOptionsJson(const RunArgs& a) {
  const nlohmann::json j = {{"sequence", a.sequence}, {"camera", a.camera},       {"realtime", a.realtime},
                            {"mode", a.mode},         {"models", a.models},       {"deterministic", a.deterministic},
                            {"strict", a.strict},     {"max_frames", a.max_frames}, {"save_masks", a.save_masks},
                            {"record", a.record},     {"viewer", a.viewer.enabled},
                            {"dense", a.dense}};
  return j.dump();
}

// SIGINT (Ctrl-C) and SIGTERM end the run at the next frame boundary (a paced or live source's wait for its next
// frame at once): mapping is stopped and the outputs are written for the frames processed so far; exit status 128 +
// the signal (130, 143). The handler only does what is async-signal-safe: it keeps the first signal's number and
// posts a semaphore, on which a watcher thread waits to request the stop (core::StopRequest wakes the waits). A
// second signal ends the program at once (the default action), after one line on stderr saying that what is on
// disk stays valid (the per-frame files are flushed line by line, the others written whole and renamed).
std::atomic<int> g_signal{0};
sem_t g_signal_posted;
// The line a second signal writes: two buffers, the one in force named by g_second_signal_line, so that the line
// can change (once the main outputs are written) while a handler may read the other one.
char g_second_signal_lines[2][1024] = {{0}};
std::size_t g_second_signal_lengths[2] = {0, 0};
std::atomic<int> g_second_signal_line{0};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

void setSecondSignalLine(const std::string& line) {
  const int next = 1 - g_second_signal_line.load();
  g_second_signal_lengths[next] = std::min(line.size(), sizeof(g_second_signal_lines[next]));
  std::copy_n(line.data(), g_second_signal_lengths[next], g_second_signal_lines[next]);
  g_second_signal_line.store(next);
}

extern "C" void onStopSignal(int signal_number) {
  int none = 0;
  if (g_signal.compare_exchange_strong(none, signal_number)) {
    sem_post(&g_signal_posted);
    return;
  }
  const int line = g_second_signal_line.load();
  const ssize_t written = write(STDERR_FILENO, g_second_signal_lines[line], g_second_signal_lengths[line]);
  (void)written;
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

// Installs onStopSignal for SIGINT and SIGTERM, and the watcher thread, for its lifetime (the run and the writing
// of its outputs). `output`: the output folder the second signal's line names.
class StopSignals {
 public:
  explicit StopSignals(const std::string& output) {
    setSecondSignalLine(fmt::format(
        "amos-slam: second signal, ending at once; what is on disk in {} stays valid (trajectory_live.txt and "
        "frames.tsv hold every frame tracked so far)\n",
        output));
    g_signal.store(0);
    sem_init(&g_signal_posted, 0, 0);
    watcher_ = std::thread([this] {
      while (sem_wait(&g_signal_posted) != 0 && errno == EINTR) {
      }
      if (g_signal.load() != 0) stop_.request();  // else: woken by the destructor
    });
    std::signal(SIGINT, onStopSignal);
    std::signal(SIGTERM, onStopSignal);
  }
  ~StopSignals() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    sem_post(&g_signal_posted);  // wakes the watcher when no signal came
    watcher_.join();
    sem_destroy(&g_signal_posted);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  core::StopRequest* request() { return &stop_; }
  int received() const { return g_signal.load(); }

 private:
  core::StopRequest stop_;
  std::thread watcher_;  // last: started once the rest exists
};

const char* signalName(int signal_number) {
  switch (signal_number) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
  }
  return "a signal";
}

void printSource(const report::SourceReport& src) {
  std::cout << fmt::format("source {}: delivered {}  processed {}  dropped {}", src.kind, src.delivered,
                           src.processed, src.dropped);
  if (!src.latency_ms.empty()) {
    std::cout << fmt::format(";  latency arrival -> pose median {:.1f} ms  p95 {:.1f} ms",
                             core::percentile(src.latency_ms, 0.5), core::percentile(src.latency_ms, 0.95));
  }
  if (src.segmentation_late > 0)
    std::cout << fmt::format(";  person masks carried on past a late network on {} frames", src.segmentation_late);
  if (!src.recorded_to.empty()) std::cout << ";  recorded to " << src.recorded_to;
  std::cout << "\n";
}

// Frames skipped as unreadable (by reason) and depth dropouts, when there were any.
void printDamagedInput(const report::RunInfo& info) {
  const io::SkippedFrames& skipped = info.skipped_frames;
  const report::DepthDropouts& dropouts = info.depth_dropouts;
  if (skipped.total() == 0 && dropouts.frames == 0) return;
  std::vector<std::string> reasons;
  for (const io::FrameProblem problem : io::kFrameProblems) {
    if (skipped.count(problem) > 0)
      reasons.push_back(fmt::format("{} {}", io::frameProblemName(problem), skipped.count(problem)));
  }
  std::cout << fmt::format("skipped frames {}{};  depth dropouts {} (tracked {}, lost {})\n", skipped.total(),
                           reasons.empty() ? "" : " (" + fmt::format("{}", fmt::join(reasons, ", ")) + ")",
                           dropouts.frames, dropouts.tracked, dropouts.lost);
}

void printSummary(const run::SequenceRunResult& r, const std::string& output) {
  const system::SlamStats s = r.slam().stats();
  const auto stages = r.slam().times().summary();
  auto median = [&](const char* name) {
    const auto it = stages.find(name);
    return it == stages.end() ? 0.0 : it->second.median_ms;
  };
  std::cout << fmt::format("frames {}  tracked {}  lost {}  relocalised {}  keyframes {}  map points {}\n", s.frames,
                           s.tracked, s.lost, s.relocalized, s.keyframes, s.map_points);
  std::cout << fmt::format("median ms per frame: extract {:.1f}  track {:.1f}  total {:.1f};  wall {:.2f} s = {:.1f} fps\n",
                           median("frame.extract"), median("frame.track"), median("frame.total"), r.info.wall_time_s,
                           r.info.wall_time_s > 0 ? s.frames / r.info.wall_time_s : 0.0);
  if (r.info.source) printSource(*r.info.source);
  printDamagedInput(r.info);
  if (r.info.evaluation) {
    const auto& e = *r.info.evaluation;
    std::cout << fmt::format("ATE RMSE {:.4f} m ({} poses)", e.ate_rmse_m, e.ate_pairs);
    if (!std::isnan(e.rpe_trans_rmse_m)) {
      std::cout << fmt::format("  RPE(1 s) {:.4f} m  {:.3f} deg ({} pairs)", e.rpe_trans_rmse_m, e.rpe_rot_rmse_deg,
                               e.rpe_pairs);
    }
    std::cout << "\n" << eval::jitterLine(e.jitter);
  }
  if (r.info.mask_accuracy) {
    const auto& m = *r.info.mask_accuracy;
    std::cout << fmt::format(
        "dynamic mask vs true movers ({} frames, {} with movers): precision {:.3f}  recall {:.3f}  IoU {:.3f};  "
        "per-frame medians {:.3f} / {:.3f} / {:.3f};  {:.2f}% of pixels marked\n",
        m.frames, m.frames_with_truth, m.precision, m.recall, m.iou, m.median_precision, m.median_recall,
        m.median_iou, 100.0 * m.dynamic_fraction);
    for (const eval::InstanceAccuracy& a : r.info.instance_accuracy) {
      std::string releases;
      for (const auto& [first, frames] : a.releases)
        releases += fmt::format(" {}@{}", frames < 0 ? std::string("never") : std::to_string(frames), first);
      std::cout << fmt::format(
          "  mover {} {} ({}): moving {} frames, recall {:.3f} precision {:.3f}; at rest {} frames, {:.1f}% marked{}\n",
          a.id, a.name, a.category, a.moving_frames, a.recall, a.precision, a.rest_frames,
          100.0 * a.rest_marked_fraction, releases.empty() ? "" : "; frames to release after a stop:" + releases);
    }
  }
  if (r.info.end.status != report::RunEnd::Status::kComplete) {
    std::cout << fmt::format("run {} after {} frames: {}; the outputs hold the frames processed until then\n",
                             report::toString(r.info.end.status), s.frames, r.info.end.reason);
  }
  std::cout << "outputs written to " << output << "\n";
}

// <output>/settings_used.yaml: every settings key as the run used it (--mode sets Dynamic.mode), below the command
// line, so that `run --config <output>/settings_used.yaml` with the same other flags repeats the run.
void writeSettingsUsed(const config::Settings& settings, const run::SequenceRunOptions& options,
                       const RunArgs& args) {
  config::writeSettingsFile(args.output + "/settings_used.yaml", run::effectiveSettings(settings, options),
                            {"The settings this run used: every key at its effective value (configs/README.md).",
                             "command line: " + commandLine(), "settings file: " + args.config,
                             "set by the command line: Dynamic.mode (--mode " + args.mode + ")",
                             "Repeat the run: the same command line with --config <this file>."});
}

// --save-map: the map as the run left it (mapping finished); returns the summary's line (its size and the time
// it took).
std::string saveMap(const system::SlamSystem& slam, const std::string& path) {
  core::Stopwatch watch;
  const mapio::MapFileSummary saved = slam.saveMap(path);
  return fmt::format("map saved to {}: {} keyframes, {} map points, {:.1f} MB in {:.0f} ms\n", path, saved.keyframes,
                     saved.map_points, saved.bytes / 1e6, watch.elapsedMs());
}

// What this run writes into --output (its manifest, report/output_folder.h).
#ifdef AMOS_HAVE_DENSE_PLUGIN
// The dense map's live cloud, flattened for the viewer's publisher (nothing without --viewer).
dense::LiveCloudCallback liveCloudToViewer(RunWatchers::DenseCloudSink sink) {
  if (!sink) return {};
  return [sink = std::move(sink)](const dense::LiveCloud& cloud) {
    std::vector<float> xyz;
    std::vector<std::uint8_t> rgb;
    xyz.reserve(3 * cloud.points.size());
    rgb.reserve(3 * cloud.points.size());
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      xyz.insert(xyz.end(), {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z()});
      rgb.insert(rgb.end(), cloud.colours[i].begin(), cloud.colours[i].end());
    }
    sink(std::move(xyz), std::move(rgb));
  };
}
#endif

std::vector<std::string> outputNames(const RunArgs& args) {
  std::vector<std::string> names = report::mainOutputNames();
  if (args.save_masks) names.insert(names.end(), {"masks", "overlays"});
#ifdef AMOS_HAVE_DENSE_PLUGIN
  if (args.dense) {
    for (const std::string& name : run::densePlugin().denseOutputNames()) names.push_back(name);
  }
#endif
  for (const std::string& name : RunWatchers::outputNames()) names.push_back(name);
  return names;
}

// The run's options from the command line (all but the observers, the progress display and the stop flag).
run::SequenceRunOptions sequenceRunOptions(const RunArgs& args) {
  run::SequenceRunOptions options;
  options.source = !args.camera.empty()          ? run::FrameSourceKind::kCamera
                   : run::isBagFile(args.sequence) ? run::FrameSourceKind::kBag
                   : args.realtime                 ? run::FrameSourceKind::kRealtime
                                                   : run::FrameSourceKind::kFolder;
  core::require(!(options.source == run::FrameSourceKind::kBag && args.realtime),
                "run --realtime: a bag is read as fast as possible (play it into amos_slam_node for a paced run)");
  core::require(args.groundtruth_topic.empty() || options.source == run::FrameSourceKind::kBag,
                fmt::format("run --groundtruth-topic {}: only for --sequence X.bag (a folder's ground truth is its "
                            "groundtruth.txt)",
                            args.groundtruth_topic));
  options.sequence_dir = args.sequence;
  options.rgb_topic = args.rgb_topic;
  options.groundtruth_topic = args.groundtruth_topic;
  options.groundtruth_parent_frame = args.groundtruth_parent_frame;
  options.groundtruth_child_frame = args.groundtruth_child_frame;
  options.depth_topic = args.depth_topic;
  options.camera_info_topic = args.camera_info_topic;
  options.camera = args.camera;
  options.record_dir = args.record;
  options.config_label = args.config;
  options.mode = args.mode;
  options.deterministic = args.deterministic;
  options.strict = args.strict;
  options.max_frames = args.max_frames;
  options.first_frame = args.first_frame;
  options.load_map = args.load_map;
  options.localize = args.localize;
  options.models_dir = args.models;
  if (args.save_masks) options.masks_output_dir = args.output;
  options.live_log_dir = args.output;
  options.overlay_count = args.overlays;
  return options;
}

// What a signal during the optional stages finds on disk, for the lines that answer it.
std::string safeFiles(const RunArgs& args, bool map_saved) {
  return fmt::format("trajectory.txt, keyframes.txt, map.ply, stats.json, settings_used.yaml{} in {}",
                     map_saved ? " and the map file " + args.save_map : "", args.output);
}

#ifdef AMOS_HAVE_DENSE_PLUGIN
// The dense map's final fusion and files, once the main outputs are on disk. A first signal during it is answered at
// once on stderr and stops the fusion; after a run a signal ended (a live session's Ctrl-C) the frames so far are
// fused, and a second signal ends the program at once.
report::OptionalStage denseStage(run::DenseRunMap& dense, run::SequenceRunResult& result, StopSignals& signals,
                                 const std::string& safe) {
  std::atomic<bool> stop{false};
  core::StopRequest::Subscription answer;
  if (signals.received() == 0) {
    answer = signals.request()->onStop([&stop, safe] {
      std::fprintf(stderr, "amos-slam: interrupted during dense fusion: %s are written; stopping the fusion\n",
                   safe.c_str());
      stop = true;
    });
  }
  spdlog::info("dense map: final fusion started; {} are written (a signal stops it)", safe);
  return dense.finishMap(result.trajectory, result.info, &stop);
}
#endif

// report.html, the last optional stage (nothing without the viewer module).
void reportStage(RunWatchers& watchers, const RunArgs& args, report::RunInfo& info) {
  if (RunWatchers::outputNames().empty()) return;
  try {
    watchers.writeReport(args.output, args.config, runOptionsJson(args));
    info.optional_stages["report"] = {};
  } catch (const std::exception& e) {
    info.optional_stages["report"] = {report::OptionalStage::Status::kFailed, e.what()};
  }
}

// The optional stages that did not end done, one line each (stdout, with the summary); a warning each too.
std::vector<std::string> optionalStageProblems(const report::RunInfo& info) {
  std::vector<std::string> problems;
  for (const auto& [name, stage] : info.optional_stages) {
    if (stage.status == report::OptionalStage::Status::kDone) continue;
    problems.push_back(fmt::format("optional stage {}: {} ({})", name, report::toString(stage.status), stage.reason));
    spdlog::warn("{}", problems.back());
  }
  return problems;
}

void runSlam(const RunArgs& args, int& exit_code) {
  core::require(!args.sequence.empty() || !args.camera.empty(),
                "run: give --sequence DIR (a recorded sequence) or --camera openni2[:URI] (a live camera)");
  const run::SequenceRunOptions source_options = sequenceRunOptions(args);
  const config::Settings settings = source_options.source == run::FrameSourceKind::kBag
                                        ? run::loadBagSettings(args.config, source_options)
                                        : run::loadSettings(args.config);
  // Before anything else runs (models, the camera, the first frame): a wrong output path is found at once, the
  // input is never written, and the output folder is this run's until it ends.
  report::refuseInsideInput(args.record, "--record", args.sequence);
  report::refuseInsideInput(args.save_map, "--save-map", args.sequence);
  report::checkOutputFile(args.save_map, "--save-map");
  const report::OutputFolderLock lock =
      report::prepareOutputFolder({args.output, args.overwrite, outputNames(args), args.sequence});
  RunWatchers watchers(args.viewer);
#ifdef AMOS_HAVE_DENSE_PLUGIN
  std::unique_ptr<run::DenseRunMap> dense_map;
  if (args.dense) {
    // The live volume exists for the live view only; without --viewer the frames are kept and fused once, at the
    // end, with the final trajectory (the same final map), and tracking shares the cores with less.
    dense::DenseOptions dense_options = settings.section<dense::DenseOptions>();
    if (!args.viewer.enabled) dense_options.live_every = 0;
    dense_map = run::densePlugin().makeDenseRunMap(dense_options, args.output,
                                                   liveCloudToViewer(watchers.denseCloudSink()));
  }
#else
  core::require(!args.dense, "run --dense: this build has no dense map (install libopen3d-dev and rebuild)");
#endif
  const bool tty = isatty(fileno(stderr)) != 0;
  run::SequenceRunOptions options = sequenceRunOptions(args);
  options.observers = watchers.observers();
#ifdef AMOS_HAVE_DENSE_PLUGIN
  if (dense_map) options.observers.push_back(dense_map.get());
#endif
  bool line_open = false;  // a progress line without its newline on the terminal
  // Progress goes to stderr: a live line on a terminal, else (a log file, a pipe) one line every --progress-every
  // frames and the last one.
  const std::size_t every = std::max<std::size_t>(1, args.progress_every);
  options.on_frame = [tty, every, &line_open](const run::SequenceProgress& p) {
    const auto& t = p.output->track;
    const std::string position = p.total > 0 ? fmt::format("{}/{}", p.frame, p.total) : std::to_string(p.frame);
    const std::string line =
        fmt::format("frame {}  {}  inliers {}  {:.1f} ms  {:.1f} fps", position, tracking::toString(t.state),
                    t.inliers, p.output->total_ms, p.elapsed_s > 0 ? p.processed / p.elapsed_s : 0.0);
    if (tty) {
      std::fprintf(stderr, "\r%-78s", line.c_str());
      line_open = true;
    } else if (p.processed % every == 0 || p.frame == p.total) {
      spdlog::info("{}", line);
    }
  };
  StopSignals signals(args.output);
  options.stop = signals.request();
  if (options.source == run::FrameSourceKind::kCamera)
    spdlog::info("live session: Ctrl-C ends it and writes the outputs");
  run::SequenceRunResult result;
  try {
    result = run::runSequence(settings, options);
  } catch (...) {
    if (line_open) std::fprintf(stderr, "\n");
    throw;
  }
  if (line_open) std::fprintf(stderr, "\n");
  if (result.info.end.status == report::RunEnd::Status::kInterrupted)
    result.info.end.reason = signalName(signals.received());
  // The main outputs first: trajectory, keyframes, map, stats, the saved map and the settings are on disk before
  // any optional stage (the dense map's final fusion, report.html) starts, so neither a failure nor a kill during
  // those loses them. An error of the saved map comes after the others are written.
  report::writeRunOutputs(args.output, result.slam(), result.info);
  std::string map_saved;
  std::exception_ptr map_error;
  if (!args.save_map.empty() && !result.failure) {
    try {
      map_saved = saveMap(result.slam(), args.save_map);
    } catch (const std::exception&) {
      map_error = std::current_exception();
    }
  }
  writeSettingsUsed(settings, options, args);
  const std::string safe = safeFiles(args, !map_saved.empty());
  setSecondSignalLine(fmt::format("amos-slam: second signal, ending at once; {} are written\n", safe));
  const int signal_before_stages = signals.received();
#ifdef AMOS_HAVE_DENSE_PLUGIN
  if (dense_map) {
    result.info.optional_stages["dense"] = denseStage(*dense_map, result, signals, safe);
    report::writeStatsJson(args.output, result.slam(), result.info);
  }
#endif
  if (signals.received() == signal_before_stages) {
    reportStage(watchers, args, result.info);
  } else if (!RunWatchers::outputNames().empty()) {
    result.info.optional_stages["report"] = {report::OptionalStage::Status::kSkipped, "a signal stopped the run"};
  }
  if (!result.info.optional_stages.empty()) report::writeStatsJson(args.output, result.slam(), result.info);
  printSummary(result, args.output);
  const std::vector<std::string> optional_problems = optionalStageProblems(result.info);
  for (const std::string& line : optional_problems) std::cout << line << "\n";
  std::cout << map_saved << std::flush;  // now, not at exit: --viewer-hold may serve for hours with stdout in a file
  if (map_error) std::rethrow_exception(map_error);
  if (signals.received() == 0) watchers.holdIfAsked();
  result.rethrowFailure();  // main() reports it (stderr) and exits non-zero, after the outputs are written
  const int signal_number = signals.received();
  if (signal_number == 0 && args.fail_on_optional && !optional_problems.empty())
    throw core::Error(fmt::format("--fail-on-optional: {}", fmt::join(optional_problems, "; ")));
  if (signal_number != 0) {
    spdlog::warn("run interrupted by {} after {} frames; the outputs in {} hold those frames",
                 signalName(signal_number), result.slam().stats().frames, args.output);
  }
  exit_code = signal_number != 0 ? 128 + signal_number : 0;
}


}  // namespace

void addRunCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "Run RGB-D SLAM over a TUM/Bonn-layout sequence or a live camera");
  auto* sequence =
      cmd->add_option("--sequence", args->sequence,
                      "Sequence folder (rgb/, depth/, rgb.txt, depth.txt) or ROS 1 bag (X.bag; docs/ros.md)")
                       ->check(CLI::ExistingPath);
  for (auto [flag, value, what] : {std::tuple{"--rgb-topic", &args->rgb_topic, "colour Image"},
                                   std::tuple{"--depth-topic", &args->depth_topic, "depth Image"},
                                   std::tuple{"--camera-info-topic", &args->camera_info_topic, "CameraInfo"}}) {
    cmd->add_option(flag, *value,
                    fmt::format("--sequence X.bag: the {} topic (default: the TUM, OpenNI2 or RealSense driver's)",
                                what))
        ->needs(sequence);
  }
  cmd->add_option("--groundtruth-topic", args->groundtruth_topic,
                  "--sequence X.bag: the ground truth from this topic (geometry_msgs/PoseStamped, TransformStamped, "
                  "nav_msgs/Odometry or tf2_msgs/TFMessage), over a groundtruth.txt beside the bag")
      ->needs(sequence);
  cmd->add_option("--groundtruth-parent-frame", args->groundtruth_parent_frame,
                  "--groundtruth-topic /tf: the world's frame (default /world, as the TUM RGB-D bags)")
      ->capture_default_str();
  cmd->add_option("--groundtruth-child-frame", args->groundtruth_child_frame,
                  "--groundtruth-topic /tf: the camera's frame (default /kinect, as the TUM RGB-D bags)")
      ->capture_default_str();
  auto* realtime = cmd->add_flag("--realtime", args->realtime,
                                 "Replay --sequence at its recorded time stamps: frames that arrive while SLAM is "
                                 "busy replace the waiting one and are counted as dropped (default: every frame, "
                                 "as fast as possible)");
  auto* camera = cmd->add_option("--camera", args->camera,
                                 "Live camera instead of --sequence: openni2 (the first device) or openni2:URI; "
                                 "Ctrl-C ends the session (no evaluation)");
  realtime->needs(sequence);
  camera->excludes(sequence);
  camera->excludes(realtime);
  cmd->add_option("--record", args->record,
                  "Also write every processed frame to this folder in TUM layout (rgb/, depth/ at the config's "
                  "DepthMapFactor, rgb.txt, depth.txt), to replay and evaluate later");
  cmd->add_option("--config", args->config, "Settings file (configs/*.yaml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--output", args->output,
                  "Output folder (created if needed; checked for writing before anything else runs; not inside "
                  "--sequence; one run at a time)")
      ->required();
  cmd->add_flag("--overwrite", args->overwrite,
                "Replace an earlier run in --output: what its run_manifest.json lists is removed first (nothing "
                "else). Without it such a folder is refused; a folder without a manifest is never emptied");
  cmd->add_option("--mode", args->mode, "Dynamic front end: none (plain SLAM) | prior (person masks) | geometry (superpixel clusters + epipolar) | full (both, default)")
      ->check(CLI::IsMember({"none", "prior", "geometry", "full"}));
  cmd->add_option("--models", args->models, "Folder with the segmentation models and the place vocabulary (Place.vocabulary is looked for here first)");
  cmd->add_flag("--deterministic", args->deterministic,
                "Bit-identical runs: local mapping in lock-step with tracking");
  cmd->add_flag("--strict", args->strict,
                "A frame that cannot be read (missing, unreadable, wrong size, depth not 16-bit) is an error that "
                "ends the run; by default it is skipped with a warning and counted in stats.json");
  cmd->add_option("--max-frames", args->max_frames, "Stop after this many frames (0 = all)")
      ->check(nonNegativeWhole());
  cmd->add_option("--first-frame", args->first_frame,
                  "Start at this frame of --sequence (0-based; the frames before it are skipped)")
      ->check(nonNegativeWhole());
  auto* load_map = cmd->add_option("--load-map", args->load_map,
                                   "Start from this saved map (see --save-map) instead of an empty one: the first "
                                   "frame is relocalised in it, and the map is extended unless --localize");
  cmd->add_flag("--localize", args->localize,
                "With --load-map: only localise in the loaded map (no new keyframes or points), relocalising "
                "from a cold start and after every loss; the trajectory holds the localised frames")
      ->needs(load_map);
  cmd->add_option("--save-map", args->save_map,
                  "Write the map at the end of the run to this file (versioned binary with a checksum; keyframes, "
                  "map points, covisibility, spanning tree and the camera), to --load-map it later");
  cmd->add_option("--progress-every", args->progress_every,
                  "When stderr is not a terminal, print a progress line every N frames (default 100); on a terminal "
                  "the progress is one live line")
      ->check(nonNegativeWhole());
  cmd->add_flag("--save-masks", args->save_masks,
                "Also write every frame's dynamic mask (masks/<rgb stamp>.png, 255 = dynamic) and overlays of a few "
                "evenly spaced frames (overlays/)");
  cmd->add_option("--overlays", args->overlays, "Overlay images written with --save-masks (default 8)")
      ->check(nonNegativeWhole());
  cmd->add_flag("--dense", args->dense,
                "Also fuse the static world into a dense map (the dynamic pixels left out) and write mesh.ply, "
                "cloud.ply, removed_points.ply and occupancy.pgm/.yaml (Dense.* settings, docs/dense.md)");
  cmd->add_flag("--fail-on-optional", args->fail_on_optional,
                "Exit with status 1 when an optional stage after the main outputs fails (the dense map or one of its "
                "files, report.html); by default such a failure is a warning in the summary and in stats.json "
                "(optional_stages)");
  cmd->add_flag("--viewer", args->viewer.enabled,
                "Serve a live view of the run (map, keyframes, trajectory, the frame with its dynamic mask, times) "
                "on http://127.0.0.1:PORT/ while it goes; the address is printed on start");
  cmd->add_option("--viewer-port", args->viewer.port, "Port of --viewer (default 8090; 0 = any free port)")
      ->check(portNumber());
  cmd->add_option("--viewer-bind", args->viewer.bind,
                  "Address --viewer listens on (default 127.0.0.1: this machine only; 0.0.0.0 = every interface)");
  cmd->add_flag("--viewer-hold", args->viewer.hold,
                "With --viewer: keep serving after the run has ended, until Ctrl-C");
  cmd->callback([args, &exit_code] { runSlam(*args, exit_code); });
}

}  // namespace amos::app
