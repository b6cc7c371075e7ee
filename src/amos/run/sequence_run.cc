#include "amos/run/sequence_run.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/eval/ground_truth_masks.h"
#include "amos/io/dataset.h"
#include "amos/io/frame_source.h"
#include "amos/io/png_reader.h"
#include "amos/io/realtime_replay.h"
#include "amos/run/bag_source.h"
#include "amos/run/live_log.h"
#include "amos/run/mask_scoring.h"
#include "amos/run/mask_writing.h"
#include "amos/run/recording.h"
#include "amos/run/trajectory_evaluation.h"
#ifdef AMOS_HAVE_OPENNI2
#include "amos/camera/openni2_source.h"
#endif

namespace amos::run {

namespace fs = std::filesystem;

namespace {

}  // namespace

config::Settings effectiveSettings(const config::Settings& settings, const SequenceRunOptions& options) {
  return api::effectiveSettings(settings, options.mode);
}

std::string sourceKindName(FrameSourceKind kind, const std::string& camera) {
  switch (kind) {
    case FrameSourceKind::kFolder: return "folder";
    case FrameSourceKind::kRealtime: return "realtime";
    case FrameSourceKind::kCamera: return parseCameraSpec(camera).driver;
    case FrameSourceKind::kBag: return "bag";
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

// The sequence's frames to run (after --first-frame and --max-frames); nothing for a live camera.
std::optional<io::SequenceIndex> indexFrames(const SequenceRunOptions& options) {
  if (options.source == FrameSourceKind::kCamera) {
    parseCameraSpec(options.camera);  // a wrong --camera is an error before any model is loaded
    return std::nullopt;
  }
  io::SequenceIndex index = io::indexSequence(options.sequence_dir);
  core::require(options.first_frame < index.frames.size() || index.frames.empty(),
                fmt::format("--first-frame {}: {} has only {} frames", options.first_frame, options.sequence_dir,
                            index.frames.size()));
  index.frames.erase(index.frames.begin(),
                     index.frames.begin() +
                         static_cast<std::ptrdiff_t>(std::min(options.first_frame, index.frames.size())));
  if (options.max_frames > 0 && index.frames.size() > options.max_frames) index.frames.resize(options.max_frames);
  return index;
}

// Settings that cannot fit the input are an error before the run, not a run that skips every frame as the wrong
// size: the first frame whose colour image's header can be read (io::pngHeaderSize; a bad first file is the
// reader's to report) must have Camera.width x Camera.height, and so must its depth image.
void checkSettingsFitTheInput(const io::SequenceIndex& index, const config::Settings& settings,
                              const SequenceRunOptions& options) {
  constexpr std::size_t kFramesLooked = 10;
  const io::ReaderOptions reader = settings.readerOptions();
  for (std::size_t i = 0; i < std::min(kFramesLooked, index.frames.size()); ++i) {
    const io::AssociatedFrame& frame = index.frames[i];
    const std::optional<cv::Size> rgb = io::pngHeaderSize(frame.rgb_file);
    if (!rgb) continue;
    const std::pair<std::string, std::optional<cv::Size>> images[] = {
        {frame.rgb_file, rgb}, {frame.depth_file, io::pngHeaderSize(frame.depth_file)}};
    for (const auto& [file, size] : images) {
      if (!size || (size->width == reader.width && size->height == reader.height)) continue;
      throw core::Error(fmt::format(
          "Camera.width x Camera.height is {}x{} in {}, but the sequence's frames are {}x{} ('{}'): set them (and "
          "the intrinsics) for the camera that recorded {}, or use its config",
          reader.width, reader.height, options.config_label.empty() ? "the settings" : options.config_label,
          size->width, size->height, file, options.sequence_dir));
    }
    return;
  }
}

// The SLAM system and its front end as amos::Slam makes them (api/engine.h): the same per-frame path.
std::unique_ptr<api::Engine> makeEngine(const config::Settings& settings, const SequenceRunOptions& options) {
  core::require(!options.localize || !options.load_map.empty(),
                "--localize needs a map to localize in (--load-map FILE)");
  api::EngineOptions o;
  o.mode = options.mode;
  o.models_dir = options.models_dir;
  o.deterministic = options.deterministic;
  o.load_map = options.load_map;
  o.localize = options.localize;
  o.after_keyframe = options.after_keyframe;
  return std::make_unique<api::Engine>(settings, o);
}

std::unique_ptr<io::FrameSource> openSource(const config::Settings& settings, const SequenceRunOptions& options,
                                            std::optional<io::SequenceIndex>& index, const BagInput& bag) {
  io::ReaderOptions reader_options = settings.readerOptions();
  reader_options.strict = options.strict;
  switch (options.source) {
    case FrameSourceKind::kFolder: return std::make_unique<io::SequenceReader>(std::move(*index), reader_options);
    case FrameSourceKind::kRealtime: return std::make_unique<io::RealtimeReplay>(std::move(*index), reader_options);
    case FrameSourceKind::kCamera: return openCamera(settings, options.camera);
    case FrameSourceKind::kBag: return bag.open(reader_options);
  }
  return nullptr;
}

// The run's own observers, made from the settings and options, and added to the controller before the caller's.
struct OwnObservers {
  std::unique_ptr<LiveLog> live_log;
  std::unique_ptr<Recording> recording;
  std::unique_ptr<MaskScoring> scoring;
  std::unique_ptr<MaskWriting> writing;
  std::unique_ptr<TrajectoryEvaluation> evaluation;

  void addTo(RunController& controller) {
    if (live_log) controller.addObserver(*live_log, /*output=*/true);
    if (recording) controller.addObserver(*recording);
    if (scoring) controller.addObserver(*scoring, /*output=*/true);
    if (writing) controller.addObserver(*writing, /*output=*/true);
    controller.addObserver(*evaluation);
  }
};

// Before the source is opened (a paced or live source starts its clock at once); MaskWriting creates its folders
// in onStart.
OwnObservers makeOwnObservers(const config::Settings& settings, const SequenceRunOptions& options,
                              const std::string& gt_file, BagInput& bag) {
  OwnObservers own;
  std::optional<eval::GroundTruthMasks> truth_masks;
  if (options.source != FrameSourceKind::kCamera) truth_masks = eval::GroundTruthMasks::find(options.sequence_dir);
  const bool save_masks = !options.masks_output_dir.empty();
  if (!options.live_log_dir.empty()) own.live_log = std::make_unique<LiveLog>(options.live_log_dir);
  if (!options.record_dir.empty())
    own.recording = std::make_unique<Recording>(options.record_dir, settings.depth_factor);
  if (truth_masks) own.scoring = std::make_unique<MaskScoring>(std::move(*truth_masks), save_masks);
  if (save_masks)
    own.writing = std::make_unique<MaskWriting>(options.masks_output_dir, options.overlay_count, own.scoring.get());
  own.evaluation = bag.ground_truth.empty()
                       ? std::make_unique<TrajectoryEvaluation>(gt_file, settings.groundtruth_format)
                       : std::make_unique<TrajectoryEvaluation>(std::move(bag.ground_truth), bag.ground_truth_source,
                                                                settings.groundtruth_format);
  return own;
}

RunStart runStart(const SequenceRunResult& result, const config::Settings& settings, const SequenceRunOptions& options,
                  std::size_t total_frames) {
  RunStart start;
  start.map = result.slam().sharedMap();
  start.camera = settings.camera;
  start.total_frames = total_frames;
  start.sequence = options.source == FrameSourceKind::kCamera ? options.camera : options.sequence_dir;
  start.mode = options.mode;
  start.loaded_map = options.load_map;
  start.localize = options.localize;
  return start;
}

// What is open during a run, for its end.
struct OpenRun {
  std::unique_ptr<io::FrameSource>& source;
  RunController& controller;
};

// A run in which no frame could be used is a failure, not a success with an empty trajectory.
std::string allSkippedMessage(const io::SkippedFrames& skipped, const SequenceRunOptions& options) {
  std::vector<std::string> reasons;
  for (const io::FrameProblem problem : io::kFrameProblems) {
    if (skipped.count(problem) > 0)
      reasons.push_back(fmt::format("{} {}", io::frameProblemName(problem), skipped.count(problem)));
  }
  return fmt::format("every frame of {} was skipped ({}): nothing was tracked; see the warnings above",
                     options.source == FrameSourceKind::kCamera ? options.camera : options.sequence_dir,
                     fmt::join(reasons, ", "));
}

// After the loop: the pipeline and the observers finished, how the run ended, the source's counts, the times, the
// trajectory and what the observers measured; then the observers' onEnd.
void finishRun(SequenceRunResult& result, OpenRun& run, LoopOutcome loop, const SequenceRunOptions& options) {
  result.pipeline().finish();
  std::exception_ptr failure = loop.failure;
  if (!failure) failure = result.slam().workerFailure();  // e.g. while the mapping drained its queue
  for (RunObserver* o : run.controller.observers()) {
    try {
      o->onStreamEnd();
    } catch (...) {
      if (!failure) failure = std::current_exception();
    }
  }
  const io::SourceStats stats = run.source->stats();
  if (!failure && !loop.interrupted && loop.processed == 0 && stats.skipped.total() > 0)
    failure = std::make_exception_ptr(core::Error(allSkippedMessage(stats.skipped, options)));
  if (failure) {
    result.failure = failure;
    result.info.end = {report::RunEnd::Status::kFailed, errorMessage(failure)};
  } else if (loop.interrupted) {
    result.info.end = {report::RunEnd::Status::kInterrupted, "stop requested"};
  }
  report::SourceReport& source_report = *result.info.source;
  source_report.delivered = stats.delivered;
  source_report.dropped = stats.dropped;
  result.info.skipped_frames = stats.skipped;
  source_report.processed = loop.processed;
  source_report.latency_ms = std::move(loop.latency_ms);
  source_report.segmentation_late = result.pipeline().segmentationLateFrames();
  run.source.reset();  // a live device is closed here
  result.info.depth_dropouts = loop.depth_dropouts;
  // The pipeline's own stages (ORB extraction and tracking CPU in every mode, the front end's in the others).
  result.info.front_end_times = &result.pipeline().times();
  if (result.pipeline().mode() != dynamic::DynamicMode::kNone)
    result.info.removed_fractions = result.pipeline().removedFractions();
  result.info.mask_outputs_s = loop.outputs_ms / 1000.0;
  result.info.wall_time_s = run.controller.runMs() / 1000.0;
  result.info.sequence = options.source == FrameSourceKind::kCamera ? options.camera : options.sequence_dir;
  result.info.mode = options.mode;
  result.info.deterministic = options.deterministic;
  result.info.config = options.config_label;
  result.trajectory = result.slam().trajectory();
  // What the observers measure never costs the run its outputs: an error here is a warning.
  for (RunObserver* o : run.controller.observers()) {
    try {
      o->addToInfo(result.trajectory, result.info);
    } catch (const std::exception& e) {
      spdlog::warn("after the run: {}; the outputs are written without it", e.what());
    }
  }
  for (RunObserver* o : run.controller.observers()) o->onEnd(result.trajectory, result.info);
}

}  // namespace

void SequenceRunResult::rethrowFailure() const {
  if (failure) std::rethrow_exception(failure);
}


SequenceRunResult runSequence(const config::Settings& settings, const SequenceRunOptions& options) {
  SequenceRunResult result;
  BagInput bag;
  std::optional<io::SequenceIndex> index;
  if (options.source == FrameSourceKind::kBag) {
    bag = indexBagInput(options, settings);
    index = bag.index;
  } else {
    index = indexFrames(options);
    if (index) checkSettingsFitTheInput(*index, settings, options);
  }
  const std::string gt_file = index ? index->groundtruth_file : std::string();
  if (index && (!index->association.file.empty() || index->association.duplicate_rows > 0))
    result.info.association = index->association;
  result.engine = makeEngine(settings, options);
  OwnObservers own = makeOwnObservers(settings, options, gt_file, bag);
  // Opened last, just before the loop: a paced or live source starts its clock at once.
  std::unique_ptr<io::FrameSource> source = openSource(settings, options, index, bag);
  const bool paced = options.source != FrameSourceKind::kFolder;
  // A paced or live source: a pose must not wait for a late person network (DynamicPipeline::setWaitForSegmentation).
  result.pipeline().setWaitForSegmentation(!paced || settings.dynamic.prior.live_wait);
  result.info.source.emplace();
  result.info.source->kind = sourceKindName(options.source, options.camera);
  result.info.source->recorded_to = options.record_dir;
  RunController controller(*source, result.pipeline(), {paced, options.max_frames, options.stop, options.on_frame});
  own.addTo(controller);
  for (RunObserver* o : options.observers) controller.addObserver(*o);
  RunStart start = runStart(result, settings, options, source->size());
  if (!options.observers.empty()) start.ground_truth = own.evaluation->groundTruthForObservers();
  controller.notifyStart(start);
  OpenRun run{source, controller};
  finishRun(result, run, controller.run(), options);
  return result;
}

}  // namespace amos::run
