#pragma once
// Runs the SLAM system over a whole TUM/Bonn-layout sequence: the loop shared by `amos-slam run`, the end-to-end
// tests and the benchmarks. Settings come from the config module; ground truth, when the sequence has it, is
// evaluated with the eval module (Bonn marker poses converted to camera poses); ground-truth mover masks, when the
// sequence has them (synthetic sequences: masks.txt, masks/, instances.json), score the front end's dynamic mask.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/io/trajectory.h"
#include "amos/report/run_report.h"
#include "amos/system/dynamic_pipeline.h"
#include "amos/system/slam_system.h"

namespace amos::report {

// The SLAM options that follow from a settings file (camera, virtual baseline, ORB; defaults elsewhere).
system::SlamOptions slamOptionsFromSettings(const config::Settings& settings, bool deterministic);

struct SequenceProgress {
  std::size_t frame = 0, total = 0;
  const system::FrameOutput* output = nullptr;
  double elapsed_s = 0;
};

struct SequenceRunOptions {
  std::string sequence_dir;
  std::string config_label;    // recorded in stats.json
  std::string mode = "none";   // dynamic front end: none | prior | geometry | full (the CLI defaults to full)
  std::string models_dir;      // --models: segmentation model folder (see dynamic/model_locator.h)
  bool deterministic = false;
  std::size_t max_frames = 0;  // 0 = all
  // --save-masks: write every frame's final dynamic mask to <masks_output_dir>/masks/ and overlays of
  // overlay_count evenly spaced frames to <masks_output_dir>/overlays/ (see mask_outputs.h). "" = do not.
  std::string masks_output_dir;
  std::size_t overlay_count = 8;
  std::function<void(const SequenceProgress&)> on_frame;  // called after every frame (progress display)
};

struct SequenceRunResult {
  std::unique_ptr<system::SlamSystem> slam;  // finished (mapping stopped)
  std::unique_ptr<system::DynamicPipeline> pipeline;  // the front end around `slam` (declared after it: dies first)
  RunInfo info;                              // wall time, evaluation when there is ground truth
  std::vector<io::StampedPose> trajectory;
};

SequenceRunResult runSequence(const config::Settings& settings, const SequenceRunOptions& options);

}  // namespace amos::report
