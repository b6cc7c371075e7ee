// amos-slam config: what the settings files can say. --keys-markdown prints the key tables of configs/README.md
// (every key with its default and meaning, made from the key lists in amos::config; experimental keys are marked);
// --keys prints one line per key (name, default, "experimental" when it is one); --update-readme FILE writes the
// tables into FILE between its marker lines; --check FILE loads a settings file as a run would.
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "amos/config/settings.h"
#include "amos/core/error.h"
#include "amos/core/whole_file.h"
#include "amos/run/settings_sections.h"
#include "commands.h"

namespace amos::app {
namespace {

struct ConfigArgs {
  bool keys_markdown = false;
  bool keys = false;
  std::string readme, check;
};

void runConfig(const ConfigArgs& args, int& exit_code) {
  if (args.keys_markdown) std::cout << config::keysMarkdown(run::settingsSections());
  if (args.keys) {
    config::Settings defaults = config::defaultSettings(run::settingsSections());
    for (const auto& section : config::settingsKeys(defaults)) {
      for (const auto& key : section.keys) {
        std::cout << key.name() << " " << (key.isRequired() ? "required" : key.defaultValue())
                  << (key.isExperimental() ? " experimental" : "") << "\n";
      }
    }
  }
  if (!args.readme.empty()) {
    const std::string text = core::readWholeFileOrThrow(args.readme, "cannot read " + args.readme);
    const std::string updated = config::withKeyTables(text, run::settingsSections());
    if (updated != text) {
      std::ofstream out(args.readme);
      out << updated;
      core::require(out.good(), "cannot write " + args.readme);
    }
    std::cout << args.readme << (updated == text ? ": key tables up to date\n" : ": key tables written\n");
  }
  if (!args.check.empty()) {
    run::loadSettings(args.check);
    std::cout << args.check << ": ok\n";
  }
  exit_code = 0;
}

}  // namespace

void addConfigCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ConfigArgs>();
  auto* cmd =
      app.add_subcommand("config", "The settings keys: print their tables, update configs/README.md, check a file");
  cmd->add_flag("--keys-markdown", args->keys_markdown,
                "Print every settings key with its default and meaning, as the markdown tables of configs/README.md");
  cmd->add_flag("--keys", args->keys,
                "Print every settings key on a line of its own: name, default, and \"experimental\" for an experiment's "
                "switch");
  cmd->add_option("--update-readme", args->readme,
                  "Write those tables into this file (configs/README.md) between its key-table marker lines")
      ->check(CLI::ExistingFile);
  cmd->add_option("--check", args->check,
                  "Load this settings file as a run would: errors name file, line and key; warnings go to stderr")
      ->check(CLI::ExistingFile);
  cmd->require_option(1, 0);
  cmd->callback([args, &exit_code] { runConfig(*args, exit_code); });
}

}  // namespace amos::app
