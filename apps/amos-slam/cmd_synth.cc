#include <iostream>

#include "commands.h"

namespace amos::app {

void addSynthCommand(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("synth", "(not available yet)");
  cmd->allow_extras();
  cmd->callback([&exit_code] {
    std::cerr << "amos-slam synth: this subcommand is not available yet in this build\n";
    exit_code = 2;
  });
}

}  // namespace amos::app
