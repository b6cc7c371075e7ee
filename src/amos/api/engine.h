#pragma once
// The SLAM system and its dynamic front end, made from a settings file's values in one place: what `amos-slam run`
// (run/sequence_run.cc) and the library's public class amos::Slam (include/amos/slam.h) both drive, so the two
// give the same trajectory for the same frames (bit-identical with `deterministic`). The run pushes frames with one
// frame of look-ahead (run/controller.h), amos::Slam one at a time (DynamicPipeline::process); the pipeline's
// result does not depend on the look-ahead (system/dynamic_pipeline.h, "Determinism").
#include <memory>
#include <string>

#include "amos/config/settings.h"
#include "amos/mapping/local_mapper.h"
#include "amos/segmentation/model_locator.h"
#include "amos/system/dynamic_pipeline.h"
#include "amos/system/slam_system.h"

namespace amos::api {

struct EngineOptions {
  std::string mode;  // dynamic front end: none | prior | geometry | full (replaces Dynamic.mode; "" = keep it)
  std::string models_dir;     // --models ("" = the installed data folder, then the usual search; modelsFolder)
  std::string installed_models_dir;  // the installed data folder ("" = installedModelsDir(): installed_data.h)
  bool deterministic = false;
  std::string load_map;       // start from this saved map ("" = an empty map)
  bool localize = false;      // only track against the loaded map (the callers require one)
  mapping::KeyFrameHook after_keyframe;  // in the mapping thread after each keyframe is mapped
  // How the caller's user names models_dir and the modes in the model search's errors (default: the command line's).
  segmentation::SourceNames model_option_names;
};

// `settings` with the options that are also settings keys applied (mode, when not "": Dynamic.mode).
config::Settings effectiveSettings(const config::Settings& settings, const std::string& mode);

class Engine {
 public:
  // Loads the vocabulary, the segmentation models (modes prior and full) and the map; throws core::Error naming
  // what is missing or wrong.
  Engine(const config::Settings& settings, const EngineOptions& options);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  system::SlamSystem& slam() { return *slam_; }
  const system::SlamSystem& slam() const { return *slam_; }
  system::DynamicPipeline& pipeline() { return *pipeline_; }
  const system::DynamicPipeline& pipeline() const { return *pipeline_; }
  // The folder the models and the vocabulary were looked for in first ("" = only the usual search).
  const std::string& modelsDir() const { return models_dir_; }

 private:
  std::string models_dir_;
  std::unique_ptr<system::SlamSystem> slam_;
  std::unique_ptr<system::DynamicPipeline> pipeline_;  // the front end around slam_ (declared after it: dies first)
};

}  // namespace amos::api
