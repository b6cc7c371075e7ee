// amos-slam synth: renders a synthetic dynamic RGB-D sequence with exact ground truth (src/amos/synth).
#include <spdlog/spdlog.h>

#include <iostream>
#include <string>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/io/image_codecs.h"
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
  bool no_depth_noise = false;
  bool no_color_noise = false;
  double depth_time_offset_ms = 0;
  double rolling_shutter_ms = 0;
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
  cmd->add_flag("--exact", args->exact,
                "No sensor noise (depth still quantised to 1/5000 m and range-limited): --no-depth-noise and "
                "--no-color-noise together");
  cmd->add_flag("--no-depth-noise", args->no_depth_noise,
                "Exact depth (no z^2 noise, no holes; still quantised to 1/5000 m and range-limited); colour unchanged");
  cmd->add_flag("--no-color-noise", args->no_color_noise, "Exact colour (no optical blur, no pixel noise); depth unchanged");
  cmd->add_flag("--disparity-quantisation", args->options.sensor.disparity.enabled,
                "Depth in the steps of a structured-light sensor's 1/8-pixel disparity (Kinect v1: baseline 7.5 cm, "
                "f 580 px, about 2.87e-3 z^2 m)");
  cmd->add_option("--depth-time-offset-ms", args->depth_time_offset_ms,
                  "Take the depth image this many milliseconds after the colour image (camera and movers then; "
                  "stamped so in depth.txt); magnitude below half a frame interval")
      ->capture_default_str();
  cmd->add_option("--rolling-shutter-ms", args->rolling_shutter_ms,
                  "Rolling-shutter readout of the colour image: row r exposed at t + (r / height - 0.5) * readout "
                  "(0 = global shutter; 20-30 ms for a Kinect-class colour sensor)")
      ->capture_default_str();
  cmd->add_option("--rolling-shutter-band", args->options.sensor.rolling_shutter_band_rows,
                  "Rows rendered at one time under a rolling shutter")
      ->capture_default_str();
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
    synth::SensorOptions& sensor = args->options.sensor;
    if (args->exact || args->no_depth_noise) sensor.depth.enabled = false;
    if (args->exact || args->no_color_noise) sensor.color.enabled = false;
    sensor.depth_time_offset_s = args->depth_time_offset_ms / 1000.0;
    sensor.rolling_shutter_s = args->rolling_shutter_ms / 1000.0;
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
      io::writeImage(args->contact_sheet, sheet);
      spdlog::info("synth: contact sheet {} ({} frames) in {:.1f} s", args->contact_sheet, sheet_options.columns,
                   sw.elapsedMs() / 1000);
    }
    exit_code = 0;
  });
}

}  // namespace amos::app
