#include "amos/api/run_outputs.h"

#include "amos/config/settings_writer.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/report/ground_truth_evaluation.h"
#include "amos/report/output_folder.h"
#include "amos/report/run_report.h"

namespace amos::api {

namespace {

report::RunInfo runInfo(const Engine& engine, const EngineRun& run, const RunDescription& d) {
  report::RunInfo info;
  info.sequence = d.sequence;
  info.config = d.config.empty() ? run.settings_file : d.config;
  info.mode = dynamic::toString(engine.pipeline().mode());
  info.deterministic = run.deterministic;
  info.wall_time_s = run.wall_time_s;
  info.depth_dropouts = run.depth_dropouts;
  if (!d.groundtruth_file.empty()) {
    info.evaluation = report::evaluateOrWarn(
        report::readGroundTruthOrWarn(d.groundtruth_file, run.settings->groundtruth_format),
        engine.slam().trajectory(), d.groundtruth_file);
  }
  // As the run's finishRun fills them from the pipeline.
  info.front_end_times = &engine.pipeline().times();
  if (engine.pipeline().mode() != dynamic::DynamicMode::kNone)
    info.removed_fractions = engine.pipeline().removedFractions();
  report::SourceReport& source = info.source.emplace();
  source.kind = d.source_kind;
  source.processed = engine.slam().stats().frames;
  source.delivered = d.delivered > 0 ? d.delivered : source.processed;
  source.dropped = d.dropped;
  source.latency_ms = d.latency_ms;
  source.segmentation_late = engine.pipeline().segmentationLateFrames();
  return info;
}

}  // namespace

void writeRunOutputs(const std::string& dir, const Engine& engine, const EngineRun& run,
                     const RunDescription& description) {
  report::writeRunOutputs(dir, engine.slam(), runInfo(engine, run, description));  // creates `dir`
  // The manifest lists the caller's own files in the folder too, so that `run --overwrite` may replace them.
  std::vector<std::string> names = report::mainOutputNames();
  names.insert(names.end(), description.other_outputs.begin(), description.other_outputs.end());
  report::writeManifest(dir, names);
  report::writeFrameLogs(dir, run.frames != nullptr ? *run.frames : std::vector<report::FrameRecord>{});
  config::writeSettingsFile(dir + "/settings_used.yaml", effectiveSettings(*run.settings, run.mode),
                            {"The settings this run used: every key at its effective value (configs/README.md).",
                             "written by amos::Slam::writeOutputs",
                             "settings file: " + (run.settings_file.empty() ? "(amos::Options::settings_yaml)"
                                                                             : run.settings_file)});
}

std::vector<std::string> runOutputNames() {
  std::vector<std::string> names = report::mainOutputNames();
  names.push_back(report::kManifestFile);
  return names;
}

}  // namespace amos::api
