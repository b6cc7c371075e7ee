#include "amos/run/sequence_run.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "amos/config/slam_options.h"
#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/segmentation/model_locator.h"
#include "amos/segmentation/segmenter_factory.h"
#include "amos/eval/bonn_ground_truth.h"
#include "amos/eval/evaluate.h"
#include "amos/eval/ground_truth_masks.h"
#include "amos/eval/instance_mask_metrics.h"
#include "amos/eval/mask_metrics.h"
#include "amos/io/dataset.h"
#include "amos/io/frame_source.h"
#include "amos/io/realtime_replay.h"
#include "amos/io/sequence_recorder.h"
#include "amos/report/mask_outputs.h"
#include "amos/run/paced_feeder.h"
#ifdef AMOS_HAVE_OPENNI2
#include "amos/camera/openni2_source.h"
#endif

namespace amos::run {

namespace fs = std::filesystem;

namespace {

// The segmenter (modes prior and full) is created, and its models loaded, before the first frame is read, so a
// missing or corrupt model is a start-up error.
std::unique_ptr<system::DynamicPipeline> makeDynamicPipeline(const config::Settings& settings,
                                                             const SequenceRunOptions& options,
                                                             system::SlamSystem& slam) {
  dynamic::DynamicOptions dynamic_options = settings.dynamic;
  dynamic_options.mode = dynamic::parseDynamicMode(options.mode);
  std::unique_ptr<segmentation::SegmentationWorker> worker;
  if (dynamic_options.mode == dynamic::DynamicMode::kPrior || dynamic_options.mode == dynamic::DynamicMode::kFull) {
    segmentation::ModelSources sources;
    sources.cli_dir = options.models_dir;
    sources.settings_dir = settings.segmentation.models_dir;
    sources.environment = segmentation::processEnvironment();
    auto segmenter =
        segmentation::createSegmenter(settings.segmentation, sources, segmentation::builtinSegmenterFactory());
    worker = std::make_unique<segmentation::SegmentationWorker>(std::move(segmenter), settings.segmentation.dilation);
  }
  return std::make_unique<system::DynamicPipeline>(slam, dynamic_options, std::move(worker));
}

}  // namespace

std::string sourceKindName(FrameSourceKind kind, const std::string& camera) {
  switch (kind) {
    case FrameSourceKind::kFolder: return "folder";
    case FrameSourceKind::kRealtime: return "realtime";
    case FrameSourceKind::kCamera: return parseCameraSpec(camera).driver;
  }
  return "?";
}

CameraSpec parseCameraSpec(const std::string& spec) {
  CameraSpec c;
  const auto colon = spec.find(':');
  c.driver = spec.substr(0, colon);
  if (colon != std::string::npos) c.uri = spec.substr(colon + 1);
  core::require(c.driver == "openni2",
                fmt::format("--camera '{}': unknown camera driver '{}' (known: openni2[:URI])", spec, c.driver));
  return c;
}

namespace {

std::unique_ptr<io::FrameSource> openCamera(const config::Settings& settings, const std::string& spec) {
  const CameraSpec camera = parseCameraSpec(spec);
#ifdef AMOS_HAVE_OPENNI2
  camera::OpenNI2Options o;
  o.uri = camera.uri;
  o.width = settings.camera.width;
  o.height = settings.camera.height;
  o.fps = static_cast<int>(std::lround(settings.fps));
  return std::make_unique<camera::OpenNI2Source>(o);
#else
  (void)settings;
  throw core::Error(fmt::format("--camera {}: this build has no OpenNI2 support (install libopenni2-dev and "
                                "configure with -DAMOS_WITH_OPENNI2=ON)",
                                spec));
#endif
}

std::string errorMessage(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown error";
  }
}

// The ground truth as camera poses for the observers; empty when there is none or it cannot be read (the
// evaluation at the end reports that).
std::vector<io::StampedPose> observedGroundTruth(const std::string& gt_file, config::GroundTruthFormat format) {
  if (gt_file.empty()) return {};
  try {
    std::vector<io::StampedPose> gt = io::readTumTrajectory(gt_file);
    if (format == config::GroundTruthFormat::kBonn) gt = eval::bonnMarkerToCamera(gt);
    return gt;
  } catch (const core::Error&) {
    return {};
  }
}

// What observers see of a processed frame: image headers are shared, the keypoints copied.
FrameSnapshot frameSnapshot(const system::ProcessedFrame& out, std::size_t total, std::size_t processed) {
  FrameSnapshot s;
  s.index = out.frame.index;
  s.total = total;
  s.processed = processed;
  s.timestamp = out.frame.timestamp;
  s.rgb_file = out.frame.rgb_file;
  s.state = out.slam.track.state;
  s.T_cw = out.slam.track.T_cw;
  s.new_keyframe = out.slam.track.new_keyframe;
  s.inliers = out.slam.track.inliers;
  s.bgr = out.frame.bgr;
  s.dynamic_mask = out.dynamic_mask;
  s.keypoints = out.keypoints;
  s.keypoints_removed = out.slam.removed_dynamic;
  s.extract_ms = out.slam.extract_ms;
  s.build_ms = out.slam.build_ms;
  s.track_ms = out.slam.track_ms;
  return s;
}

double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

void SequenceRunResult::rethrowFailure() const {
  if (failure) std::rethrow_exception(failure);
}

SequenceRunResult runSequence(const config::Settings& settings, const SequenceRunOptions& options) {
  SequenceRunResult result;
  const bool live = options.source == FrameSourceKind::kCamera;
  std::optional<io::SequenceIndex> index;
  if (!live) {
    index = io::indexSequence(options.sequence_dir);
    core::require(options.first_frame < index->frames.size() || index->frames.empty(),
                  fmt::format("--first-frame {}: {} has only {} frames", options.first_frame, options.sequence_dir,
                              index->frames.size()));
    index->frames.erase(index->frames.begin(),
                        index->frames.begin() + static_cast<std::ptrdiff_t>(std::min(options.first_frame, index->frames.size())));
    if (options.max_frames > 0 && index->frames.size() > options.max_frames) index->frames.resize(options.max_frames);
  } else {
    parseCameraSpec(options.camera);  // a wrong --camera is an error before any model is loaded
  }
  const std::string gt_file = index ? index->groundtruth_file : std::string();
  if (index && !index->association.file.empty()) result.info.association = index->association;
  system::SlamOptions slam_options = config::slamOptionsFromSettings(settings, options.deterministic);
  slam_options.after_keyframe = options.after_keyframe;
  slam_options.tracking.localization_only = options.localize;
  core::require(!options.localize || !options.load_map.empty(), "--localize needs a map to localize in (--load-map FILE)");
  result.slam = std::make_unique<system::SlamSystem>(slam_options);
  if (!options.load_map.empty()) {
    core::Stopwatch watch;
    const mapio::MapFileSummary loaded = result.slam->loadMap(options.load_map);
    spdlog::info("map {}: {} keyframes, {} map points, loaded in {:.0f} ms{}", options.load_map, loaded.keyframes,
                 loaded.map_points, watch.elapsedMs(), options.localize ? " (localization only)" : "");
  }
  result.pipeline = makeDynamicPipeline(settings, options, *result.slam);
  std::optional<eval::GroundTruthMasks> truth_masks;
  if (!live) truth_masks = eval::GroundTruthMasks::find(options.sequence_dir);
  std::optional<io::SequenceRecorder> recorder;
  if (!options.record_dir.empty()) recorder.emplace(options.record_dir, settings.depth_factor);
  // Created last, just before the loop: a paced or live source starts its clock at once.
  io::ReaderOptions reader_options = settings.readerOptions();
  reader_options.strict = options.strict;
  std::unique_ptr<io::FrameSource> source;
  switch (options.source) {
    case FrameSourceKind::kFolder:
      source = std::make_unique<io::SequenceReader>(std::move(*index), reader_options);
      break;
    case FrameSourceKind::kRealtime:
      source = std::make_unique<io::RealtimeReplay>(std::move(*index), reader_options);
      break;
    case FrameSourceKind::kCamera:
      source = openCamera(settings, options.camera);
      break;
  }
  const bool paced = options.source != FrameSourceKind::kFolder;
  // A paced or live source: a pose must not wait for a late person network (DynamicPipeline::setWaitForSegmentation).
  result.pipeline->setWaitForSegmentation(!paced || settings.dynamic.prior.live_wait);
  std::optional<report::MaskOutputWriter> mask_writer;
  if (!options.masks_output_dir.empty())
    mask_writer.emplace(options.masks_output_dir, source->size(), options.overlay_count);
  report::SourceReport source_report;
  source_report.kind = sourceKindName(options.source, options.camera);
  source_report.recorded_to = options.record_dir;
  eval::MaskAccuracyAccumulator mask_accuracy;
  eval::InstanceAccuracyAccumulator instance_accuracy;
  if (truth_masks)
    for (const eval::GroundTruthInstance& inst : truth_masks->instances())
      instance_accuracy.describe(inst.id, inst.category, inst.name);
  if (!options.observers.empty()) {
    RunStart start;
    start.map = result.slam->sharedMap();
    start.camera = settings.camera;
    start.total_frames = source->size();
    start.sequence = live ? options.camera : options.sequence_dir;
    start.mode = options.mode;
    start.loaded_map = options.load_map;
    start.localize = options.localize;
    start.ground_truth = observedGroundTruth(gt_file, settings.groundtruth_format);
    for (RunObserver* o : options.observers) o->onStart(start);
  }
  core::Stopwatch wall;
  double last_frame_ms = 0;  // wall.elapsedMs() when the previous frame was done
  double outputs_ms = 0;  // mask scoring and writing, kept out of the run's wall time
  std::size_t n = 0;
  auto stopped = [&] { return options.stop != nullptr && options.stop->load(); };
  system::DynamicPipeline& pipeline = *result.pipeline;
  // Everything done with a processed frame; false when the run should end (--max-frames reached).
  auto consume = [&](const system::ProcessedFrame& out) {
    const io::RgbdFrame& frame = out.frame;
    source_report.latency_ms.push_back(msSince(frame.arrival));
    if (options.source != FrameSourceKind::kFolder)
      spdlog::debug("frame {}: {:.1f} ms from arrival to pose", frame.index, source_report.latency_ms.back());
    ++n;
    if (frame.depth_dropout) {
      report::DepthDropouts& d = result.info.depth_dropouts;
      ++d.frames;
      d.tracked += out.slam.track.state == tracking::TrackingState::kOk;
      d.lost += out.slam.track.state == tracking::TrackingState::kLost;
    }
    if (recorder) recorder->add(frame);
    core::Stopwatch outputs;
    cv::Mat truth;
    if (truth_masks && (mask_writer || !out.dynamic_mask.empty())) {
      if (const auto k = truth_masks->frameAt(frame.timestamp)) {
        const cv::Mat ids = truth_masks->instanceMask(*k);
        const std::vector<bool> moving = truth_masks->movingIds(*k);
        truth = eval::GroundTruthMasks::moverMask(ids, moving);
        if (!out.dynamic_mask.empty()) instance_accuracy.add(*k, out.dynamic_mask, ids, moving);
      }
    }
    if (!truth.empty() && !out.dynamic_mask.empty()) {
      mask_accuracy.add(out.dynamic_mask, truth);
      const eval::MaskCounts& c = mask_accuracy.perFrame().back();
      spdlog::debug("frame {}: dynamic mask against the truth: {} true, {} found, {} wrongly marked", out.frame.index,
                    c.true_positive + c.false_negative, c.true_positive, c.false_positive);
    }
    if (mask_writer) mask_writer->add(frame.index, frame.rgb_file, frame.bgr, out.dynamic_mask, out.prior_mask, truth);
    outputs_ms += outputs.elapsedMs();
    if (!options.observers.empty()) {
      const double now_ms = wall.elapsedMs();
      FrameSnapshot snapshot = frameSnapshot(out, source->size(), n);
      snapshot.frame_ms = now_ms - last_frame_ms;
      snapshot.elapsed_s = now_ms / 1000.0;
      last_frame_ms = now_ms;
      for (RunObserver* o : options.observers) o->onFrame(snapshot);
    }
    if (options.on_frame)
      options.on_frame({frame.index + 1, source->size(), n, &out.slam, (wall.elapsedMs() - outputs_ms) / 1000.0});
    return options.max_frames == 0 || n < options.max_frames;  // a live source has no end of its own
  };
  // Pushes the source's next frame into the pipeline's stage A (folder). A source error (a frame that cannot be
  // read with --strict) ends the stream: the frames already pushed are still processed, then the run ends with
  // that error.
  std::exception_ptr source_failure;
  auto feed = [&] {
    if (source_failure) return;
    std::optional<io::RgbdFrame> f;
    try {
      f = source->next();
    } catch (...) {
      source_failure = std::current_exception();
    }
    if (f) pipeline.push(std::move(*f));
  };
  // Any other error from here on (a stage-A lane's or the mapping thread's failure, a paced source's error after
  // the frames it delivered) ends the loop like a stop does: what was processed so far is finished and kept.
  std::exception_ptr failure;
  bool interrupted = false;
  try {
    if (paced) {
      // A feeder thread hands frames to stage A as they arrive (paced_feeder.h).
      PacedFeeder feeder(*source, pipeline);
      while (!(interrupted = stopped()) && feeder.nextForStageB())
        if (!consume(pipeline.processNext())) break;
    } else {
      // One frame of look-ahead: stage A of frame k+1 runs while frame k is in stage B.
      feed();
      while (pipeline.waiting() > 0 && !(interrupted = stopped())) {
        if (pipeline.waiting() < 2) feed();
        if (!consume(pipeline.processNext())) break;
      }
    }
  } catch (...) {
    failure = std::current_exception();
  }
  result.pipeline->finish();
  if (!failure) failure = source_failure;
  if (!failure) failure = result.slam->workerFailure();  // e.g. while the mapping drained its queue
  if (recorder) {
    try {
      recorder->finish();
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) {
    result.failure = failure;
    result.info.end = {report::RunEnd::Status::kFailed, errorMessage(failure)};
  } else if (interrupted) {
    result.info.end = {report::RunEnd::Status::kInterrupted, "stop requested"};
  }
  const io::SourceStats stats = source->stats();
  source_report.delivered = stats.delivered;
  source_report.dropped = stats.dropped;
  result.info.skipped_frames = stats.skipped;
  source_report.processed = n;
  source_report.segmentation_late = result.pipeline->segmentationLateFrames();
  source.reset();  // a live device is closed here
  result.info.source = std::move(source_report);
  // The pipeline's own stages (ORB extraction and tracking CPU in every mode, the front end's in the others).
  result.info.front_end_times = &result.pipeline->times();
  if (result.pipeline->mode() != dynamic::DynamicMode::kNone)
    result.info.removed_fractions = result.pipeline->removedFractions();
  if (!mask_accuracy.empty()) result.info.mask_accuracy = mask_accuracy.summary();
  if (!instance_accuracy.empty()) result.info.instance_accuracy = instance_accuracy.summary();
  result.info.mask_outputs_s = outputs_ms / 1000.0;
  result.info.wall_time_s = (wall.elapsedMs() - outputs_ms) / 1000.0;
  result.info.sequence = live ? options.camera : options.sequence_dir;
  result.info.config = options.config_label;
  result.info.mode = options.mode;
  result.info.deterministic = options.deterministic;
  result.trajectory = result.slam->trajectory();
  if (!gt_file.empty() && result.trajectory.size() >= 2) {
    std::vector<io::StampedPose> gt = io::readTumTrajectory(gt_file);
    if (settings.groundtruth_format == config::GroundTruthFormat::kBonn) gt = eval::bonnMarkerToCamera(gt);
    try {
      result.info.evaluation = eval::evaluate(gt, result.trajectory);
    } catch (const core::Error& e) {
      spdlog::warn("no evaluation against {}: {}", gt_file, e.what());
    }
  }
  for (RunObserver* o : options.observers) o->onEnd(result.trajectory, result.info);
  return result;
}

}  // namespace amos::run
