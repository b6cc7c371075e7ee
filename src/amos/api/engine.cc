#include "amos/api/engine.h"

#include <spdlog/spdlog.h>

#include <utility>

#include "amos/api/installed_data.h"
#include "amos/config/slam_options.h"
#include "amos/core/stage_timer.h"
#include "amos/segmentation/model_locator.h"
#include "amos/segmentation/segmenter_factory.h"

namespace amos::api {

namespace {

std::unique_ptr<system::SlamSystem> makeSlam(const config::Settings& settings, const EngineOptions& options,
                                             const std::string& models_dir) {
  system::SlamOptions slam_options = config::slamOptionsFromSettings(settings, options.deterministic, models_dir);
  slam_options.after_keyframe = options.after_keyframe;
  slam_options.tracking.localization_only = options.localize;
  auto slam = std::make_unique<system::SlamSystem>(slam_options);
  if (!options.load_map.empty()) {
    core::Stopwatch watch;
    const mapio::MapFileSummary loaded = slam->loadMap(options.load_map);
    spdlog::info("map {}: {} keyframes, {} map points, loaded in {:.0f} ms{}", options.load_map, loaded.keyframes,
                 loaded.map_points, watch.elapsedMs(), options.localize ? " (localization only)" : "");
  }
  return slam;
}

// The segmenter (modes prior and full) is created, and its models loaded, before the first frame, so a missing or
// corrupt model is a start-up error.
std::unique_ptr<system::DynamicPipeline> makeDynamicPipeline(const config::Settings& used,
                                                             const segmentation::ModelSources& sources,
                                                             system::SlamSystem& slam) {
  std::unique_ptr<segmentation::SegmentationWorker> worker;
  if (used.dynamic.mode == dynamic::DynamicMode::kPrior || used.dynamic.mode == dynamic::DynamicMode::kFull) {
    auto segmenter =
        segmentation::createSegmenter(used.segmentation, sources, segmentation::builtinSegmenterFactory());
    worker = std::make_unique<segmentation::SegmentationWorker>(std::move(segmenter), used.segmentation.dilation);
  }
  return std::make_unique<system::DynamicPipeline>(slam, used.dynamic, std::move(worker));
}

}  // namespace

config::Settings effectiveSettings(const config::Settings& settings, const std::string& mode) {
  config::Settings used = settings;
  if (!mode.empty()) used.dynamic.mode = dynamic::parseDynamicMode(mode);
  return used;
}

Engine::Engine(const config::Settings& settings, const EngineOptions& options) {
  const config::Settings used = effectiveSettings(settings, options.mode);
  models_dir_ = modelsFolder(options.models_dir, settings.segmentation.models_dir,
                             options.installed_models_dir.empty() ? installedModelsDir() : options.installed_models_dir);
  slam_ = makeSlam(used, options, models_dir_);
  segmentation::ModelSources sources;
  sources.cli_dir = models_dir_;
  sources.settings_dir = used.segmentation.models_dir;
  sources.environment = segmentation::processEnvironment();
  sources.names = options.model_option_names;
  pipeline_ = makeDynamicPipeline(used, sources, *slam_);
}

Engine::~Engine() = default;

}  // namespace amos::api
