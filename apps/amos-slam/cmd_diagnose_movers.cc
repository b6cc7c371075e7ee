// amos-slam diagnose-movers: why the geometric stage misses movers on a synthetic sequence (issue 16). All work is
// in amos::report (mover_diagnosis.h) and amos::dynamic (mover_diagnostics.h).
#include <iostream>
#include <memory>
#include <string>

#include "amos/config/settings.h"
#include "amos/run/settings_sections.h"
#include "amos/report/mover_diagnosis.h"
#include "commands.h"

namespace amos::app {

void addDiagnoseMoversCommand(CLI::App& app, int& exit_code) {
  struct Args {
    std::string config;
    report::MoverDiagnosisOptions options;
    bool summary_only = false;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand(
      "diagnose-movers",
      "Run the geometric front end on a synthetic sequence with its true poses and print, per moving instance and "
      "frame, what each stage made of it (tracks on it, its clusters' scores and decisions, how much the mask "
      "covers) and the first stage that lost it");
  cmd->add_option("--sequence", args->options.sequence_dir, "Synthetic sequence folder (amos-slam synth)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--config", args->config, "Settings file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--first", args->options.first_frame, "First frame judged")->capture_default_str();
  cmd->add_option("--last", args->options.last_frame, "Last frame judged (-1 = to the end)")->capture_default_str();
  cmd->add_flag("--exact-initial", args->options.exact_initial,
                "Initial pose = the true pose (default: constant velocity from the last two true poses)");
  cmd->add_option("--images", args->options.images_dir,
                  "Also write a picture of each frame's decision there (<frame>.png: green mover marked, red static "
                  "world marked, blue mover missed, white outlines the dynamic clusters, dots the tracks by their "
                  "error under the judged pose: green below the confirmation threshold, yellow below 3x, red beyond)");
  cmd->add_flag("--summary", args->summary_only, "Print the per-instance summary only");
  cmd->callback([args, &exit_code] {
    args->options.per_frame = !args->summary_only;
    report::diagnoseSequenceMovers(run::loadSettings(args->config), args->options, std::cout);
    exit_code = 0;
  });
}

}  // namespace amos::app
