#include "amos/report/sequence_run.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/dynamic/model_locator.h"
#include "amos/dynamic/segmenter_factory.h"
#include "amos/eval/bonn_ground_truth.h"
#include "amos/eval/evaluate.h"
#include "amos/eval/ground_truth_masks.h"
#include "amos/eval/mask_metrics.h"
#include "amos/io/dataset.h"
#include "amos/report/mask_outputs.h"

namespace amos::report {

system::SlamOptions slamOptionsFromSettings(const config::Settings& settings, bool deterministic) {
  system::SlamOptions o;
  o.camera = settings.camera;
  o.sensor.bf = settings.bf;
  o.sensor.th_depth = settings.th_depth;
  o.orb = settings.orb;
  o.tracking = settings.tracking;
  o.mapping = settings.mapping;
  o.loop = settings.loop;
  o.covisibility = settings.covisibility;
  o.deterministic = deterministic;
  return o;
}

namespace {

// The segmenter (modes prior and full) is created, and its models loaded, before the first frame is read, so a
// missing or corrupt model is a start-up error.
std::unique_ptr<system::DynamicPipeline> makeDynamicPipeline(const config::Settings& settings,
                                                             const SequenceRunOptions& options,
                                                             system::SlamSystem& slam) {
  dynamic::DynamicOptions dynamic_options = settings.dynamic;
  dynamic_options.mode = dynamic::parseDynamicMode(options.mode);
  std::unique_ptr<dynamic::SegmentationWorker> worker;
  if (dynamic_options.mode == dynamic::DynamicMode::kPrior || dynamic_options.mode == dynamic::DynamicMode::kFull) {
    dynamic::ModelSources sources;
    sources.cli_dir = options.models_dir;
    sources.settings_dir = settings.segmentation.models_dir;
    sources.environment = dynamic::processEnvironment();
    auto segmenter = dynamic::createSegmenter(settings.segmentation, sources, dynamic::builtinSegmenterFactory());
    worker = std::make_unique<dynamic::SegmentationWorker>(std::move(segmenter), settings.segmentation.dilation);
  }
  return std::make_unique<system::DynamicPipeline>(slam, dynamic_options, std::move(worker));
}

}  // namespace

SequenceRunResult runSequence(const config::Settings& settings, const SequenceRunOptions& options) {
  SequenceRunResult result;
  io::SequenceIndex index = io::indexSequence(options.sequence_dir);
  if (options.max_frames > 0 && index.frames.size() > options.max_frames) index.frames.resize(options.max_frames);
  const std::string gt_file = index.groundtruth_file;
  result.slam = std::make_unique<system::SlamSystem>(slamOptionsFromSettings(settings, options.deterministic));
  result.pipeline = makeDynamicPipeline(settings, options, *result.slam);
  const std::optional<eval::GroundTruthMasks> truth_masks = eval::GroundTruthMasks::find(options.sequence_dir);
  io::SequenceReader reader(std::move(index), settings.readerOptions());
  std::optional<MaskOutputWriter> mask_writer;
  if (!options.masks_output_dir.empty())
    mask_writer.emplace(options.masks_output_dir, reader.size(), options.overlay_count);
  eval::MaskAccuracyAccumulator mask_accuracy;
  core::Stopwatch wall;
  double outputs_ms = 0;  // mask scoring and writing, kept out of the run's wall time
  std::size_t n = 0;
  // One frame of look-ahead: the pipeline starts segmenting frame k+1 while it tracks frame k.
  std::optional<io::RgbdFrame> frame = reader.next();
  for (; frame; ++n) {
    std::optional<io::RgbdFrame> next = reader.next();
    const system::DynamicFrameOutput out = result.pipeline->process(*frame, next ? &*next : nullptr);
    core::Stopwatch outputs;
    cv::Mat truth;
    if (truth_masks && (mask_writer || !out.dynamic_mask.empty())) {
      if (const auto k = truth_masks->frameAt(frame->timestamp)) truth = truth_masks->moverMask(*k);
    }
    if (!truth.empty() && !out.dynamic_mask.empty()) mask_accuracy.add(out.dynamic_mask, truth);
    if (mask_writer) mask_writer->add(n, frame->rgb_file, frame->bgr, out.dynamic_mask, out.prior_mask, truth);
    outputs_ms += outputs.elapsedMs();
    if (options.on_frame)
      options.on_frame({n + 1, reader.size(), &out.slam, (wall.elapsedMs() - outputs_ms) / 1000.0});
    frame = std::move(next);
  }
  result.pipeline->finish();
  if (result.pipeline->mode() != dynamic::DynamicMode::kNone) {
    result.info.front_end_times = &result.pipeline->times();
    result.info.removed_fractions = result.pipeline->removedFractions();
  }
  if (!mask_accuracy.empty()) result.info.mask_accuracy = mask_accuracy.summary();
  result.info.mask_outputs_s = outputs_ms / 1000.0;
  result.info.wall_time_s = (wall.elapsedMs() - outputs_ms) / 1000.0;
  result.info.sequence = options.sequence_dir;
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
  return result;
}

}  // namespace amos::report
