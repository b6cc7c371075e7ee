// amos-slam run: SLAM over one RGB-D sequence. Writes trajectory.txt, keyframes.txt, map.ply and stats.json into
// --output (with --save-masks also masks/ and overlays/) and prints ATE / RPE when the sequence has ground truth
// and the dynamic mask's pixel precision / recall / IoU when it has ground-truth mover masks. All work is in
// amos::report / amos::system.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "amos/config/settings.h"
#include "amos/report/run_report.h"
#include "amos/report/sequence_run.h"
#include "commands.h"

namespace amos::app {
namespace {

struct RunArgs {
  std::string sequence, config, output, mode = "full", models;
  bool deterministic = false, save_masks = false;
  std::size_t max_frames = 0, overlays = 8;
};

void printSummary(const report::SequenceRunResult& r, const std::string& output) {
  const system::SlamStats s = r.slam->stats();
  const auto stages = r.slam->times().summary();
  auto median = [&](const char* name) {
    const auto it = stages.find(name);
    return it == stages.end() ? 0.0 : it->second.median_ms;
  };
  std::cout << fmt::format("frames {}  tracked {}  lost {}  relocalised {}  keyframes {}  map points {}\n", s.frames,
                           s.tracked, s.lost, s.relocalized, s.keyframes, s.map_points);
  std::cout << fmt::format("median ms per frame: extract {:.1f}  track {:.1f}  total {:.1f};  wall {:.2f} s = {:.1f} fps\n",
                           median("frame.extract"), median("frame.track"), median("frame.total"), r.info.wall_time_s,
                           r.info.wall_time_s > 0 ? s.frames / r.info.wall_time_s : 0.0);
  if (r.info.evaluation) {
    const auto& e = *r.info.evaluation;
    std::cout << fmt::format("ATE RMSE {:.4f} m ({} poses)", e.ate_rmse_m, e.ate_pairs);
    if (!std::isnan(e.rpe_trans_rmse_m)) {
      std::cout << fmt::format("  RPE(1 s) {:.4f} m  {:.3f} deg ({} pairs)", e.rpe_trans_rmse_m, e.rpe_rot_rmse_deg,
                               e.rpe_pairs);
    }
    std::cout << "\n";
  }
  if (r.info.mask_accuracy) {
    const auto& m = *r.info.mask_accuracy;
    std::cout << fmt::format(
        "dynamic mask vs true movers ({} frames, {} with movers): precision {:.3f}  recall {:.3f}  IoU {:.3f};  "
        "per-frame medians {:.3f} / {:.3f} / {:.3f};  {:.2f}% of pixels marked\n",
        m.frames, m.frames_with_truth, m.precision, m.recall, m.iou, m.median_precision, m.median_recall,
        m.median_iou, 100.0 * m.dynamic_fraction);
  }
  std::cout << "outputs written to " << output << "\n";
}

void runSlam(const RunArgs& args, int& exit_code) {
  const config::Settings settings = config::loadSettings(args.config);
  const bool tty = isatty(fileno(stderr)) != 0;
  report::SequenceRunOptions options;
  options.sequence_dir = args.sequence;
  options.config_label = args.config;
  options.mode = args.mode;
  options.deterministic = args.deterministic;
  options.max_frames = args.max_frames;
  options.models_dir = args.models;
  if (args.save_masks) options.masks_output_dir = args.output;
  options.overlay_count = args.overlays;
  options.on_frame = [tty](const report::SequenceProgress& p) {
    const auto& t = p.output->track;
    const std::string line =
        fmt::format("frame {}/{}  {}  inliers {}  {:.1f} ms  {:.1f} fps", p.frame, p.total,
                    tracking::toString(t.state), t.inliers, p.output->total_ms,
                    p.elapsed_s > 0 ? p.frame / p.elapsed_s : 0.0);
    if (tty) {
      std::fprintf(stderr, "\r%-78s", line.c_str());
      if (p.frame == p.total) std::fprintf(stderr, "\n");
    } else if (p.frame % 100 == 0 || p.frame == p.total) {
      spdlog::info("{}", line);
    }
  };
  const report::SequenceRunResult result = report::runSequence(settings, options);
  report::writeRunOutputs(args.output, *result.slam, result.info);
  printSummary(result, args.output);
  exit_code = 0;
}

}  // namespace

void addRunCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand("run", "Run RGB-D SLAM over a TUM/Bonn-layout sequence");
  cmd->add_option("--sequence", args->sequence, "Sequence folder (rgb/, depth/, rgb.txt, depth.txt)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--config", args->config, "Settings file (configs/*.yaml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--output", args->output, "Output folder (created if needed)")->required();
  cmd->add_option("--mode", args->mode, "Dynamic front end: none (plain SLAM) | prior (person masks) | geometry (superpixel clusters + epipolar) | full (both, default)")
      ->check(CLI::IsMember({"none", "prior", "geometry", "full"}));
  cmd->add_option("--models", args->models, "Folder with the segmentation models");
  cmd->add_flag("--deterministic", args->deterministic,
                "Bit-identical runs: local mapping in lock-step with tracking");
  cmd->add_option("--max-frames", args->max_frames, "Stop after this many frames (0 = all)");
  cmd->add_flag("--save-masks", args->save_masks,
                "Also write every frame's dynamic mask (masks/<rgb stamp>.png, 255 = dynamic) and overlays of a few "
                "evenly spaced frames (overlays/)");
  cmd->add_option("--overlays", args->overlays, "Overlay images written with --save-masks (default 8)");
  cmd->callback([args, &exit_code] { runSlam(*args, exit_code); });
}

}  // namespace amos::app
