// amos-slam synth: renders a synthetic dynamic RGB-D sequence with exact ground truth (src/amos/synth).
#include <spdlog/spdlog.h>

#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/synth/contact_sheet.h"
#include "amos/synth/presets.h"
#include "amos/synth/sequence.h"
#include "commands.h"

namespace amos::app {

namespace {
struct SynthArgs {
  synth::SequenceOptions options;
  std::string output;
  std::string contact_sheet;
  int contact_columns = 6;
  bool list = false;
  bool no_movers = false;
  bool exact = false;
};

void listPresets() {
  for (const synth::Preset& p : synth::allPresets())
    std::cout << p.name << "  (" << synth::toString(p.motion) << ", " << p.default_frames
              << " frames, static twin: " << p.static_counterpart << ")\n    " << p.description << "\n";
}
}  // namespace

void addSynthCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SynthArgs>();
  auto* cmd = app.add_subcommand(
      "synth",
      "Render a synthetic dynamic RGB-D sequence (TUM layout + per-pixel instance masks + exact ground truth)");
  cmd->add_flag("--list", args->list, "List the presets and their static counterparts, then exit");
  cmd->add_option("--preset", args->options.preset, "Preset name (see --list)")->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "Seed: room, textures, paths, movers and noise")->capture_default_str();
  cmd->add_option("--frames", args->options.frames, "Number of frames (0 = the preset's default)")
      ->capture_default_str();
  cmd->add_option("--output", args->output, "Output folder (TUM layout)");
  cmd->add_flag("--no-movers", args->no_movers,
                "Render the preset's static counterpart: same room and camera path, nothing moving");
  cmd->add_option("--photos", args->options.photo_dir,
                  "Folder of photographs (searched recursively) for posters, pictures and screens; note that "
                  "photos showing people put people on the walls");
  cmd->add_option("--person-cutouts", args->options.person_cutout_dir,
                  "Folder with rgb/ and mask/ person cut-outs (e.g. ../shared/data/person_masks) worn by the people");
  cmd->add_flag("--motion-blur", args->options.sensor.motion_blur, "Average the colour over the exposure time");
  cmd->add_flag("--exact", args->exact, "No sensor noise (depth still quantised to 1/5000 m and range-limited)");
  cmd->add_option("--contact-sheet", args->contact_sheet, "Write a PNG contact sheet of frames, depth and masks");
  cmd->add_option("--contact-columns", args->contact_columns, "Frames on the contact sheet")->capture_default_str();
  cmd->callback([args, &exit_code] {
    if (args->list) {
      listPresets();
      exit_code = 0;
      return;
    }
    if (args->output.empty() && args->contact_sheet.empty())
      throw core::Error("synth: give --output DIR and/or --contact-sheet FILE.png (or --list)");
    args->options.movers = !args->no_movers;
    if (args->exact) {
      args->options.sensor.depth.enabled = false;
      args->options.sensor.color.enabled = false;
    }
    if (!args->output.empty()) {
      const synth::SequenceSummary s = synth::renderSequence(args->options, args->output);
      spdlog::info(
          "synth: {} frames of '{}' (seed {}) in {:.1f} s -> {}; setup {:.0f} ms, render {:.1f} ms/frame, "
          "write {:.1f} ms/frame",
          s.frames, args->options.preset, args->options.seed, s.total_s, args->output, s.setup_ms,
          s.render_ms_per_frame, s.write_ms_per_frame);
    }
    if (!args->contact_sheet.empty()) {
      core::Stopwatch sw;
      const synth::SequenceGenerator generator(args->options);
      synth::ContactSheetOptions sheet_options;
      sheet_options.columns = args->contact_columns;
      const cv::Mat sheet = synth::contactSheet(generator, sheet_options);
      core::require(cv::imwrite(args->contact_sheet, sheet), "synth: cannot write " + args->contact_sheet);
      spdlog::info("synth: contact sheet {} ({} frames) in {:.1f} s", args->contact_sheet, sheet_options.columns,
                   sw.elapsedMs() / 1000);
    }
    exit_code = 0;
  });
}

}  // namespace amos::app
