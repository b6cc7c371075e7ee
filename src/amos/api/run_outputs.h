#pragma once
// amos::Slam::writeOutputs (include/amos/slam.h): `amos-slam run`'s output files from an api::Engine and the frames
// the Slam kept, through the code the run writes them with (report::writeRunOutputs; report::writeFrameLogs for
// trajectory_live.txt and frames.tsv; config::writeSettingsFile for settings_used.yaml; report::writeManifest).
#include <string>
#include <vector>

#include "amos/api/engine.h"
#include "amos/config/settings.h"
#include "amos/report/frame_log.h"
#include "amos/report/run_report.h"
#include "amos/slam.h"

namespace amos::api {

// What the Slam knows of its run besides the engine.
struct EngineRun {
  const config::Settings* settings = nullptr;  // as read, with the overrides
  std::string settings_file;                   // Options::settings_file ("" = settings_yaml)
  std::string mode;                            // EngineOptions::mode ("" = the settings')
  bool deterministic = false;
  double wall_time_s = 0;                      // first frame to finish() (or now)
  const std::vector<report::FrameRecord>* frames = nullptr;  // every frame processed, in order (run's per-frame log)
  report::DepthDropouts depth_dropouts;
};

void writeRunOutputs(const std::string& dir, const Engine& engine, const EngineRun& run,
                     const RunDescription& description);
std::vector<std::string> runOutputNames();

}  // namespace amos::api
