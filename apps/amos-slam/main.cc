// amos-slam: command-line front end. See README.md for the subcommands.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "amos/core/error.h"
#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"Amos-SLAM: RGB-D SLAM for scenes with moving people and objects"};
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Print debug messages");
  int exit_code = 0;
  amos::app::addRunCommand(app, exit_code);
  amos::app::addEvalCommand(app, exit_code);
  amos::app::addSynthCommand(app, exit_code);
  amos::app::addSegmentCommand(app, exit_code);
  app.parse_complete_callback([&] { spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info); });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const amos::core::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << "\n";
    return 3;
  }
  return exit_code;
}
