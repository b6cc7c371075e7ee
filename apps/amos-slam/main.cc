// amos-slam: command-line front end. See docs/usage.md for the subcommands.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <exception>
#include <iostream>

#include "amos/api/allocator_tuning.h"
#include "amos/core/error.h"
#include "commands.h"

int main(int argc, char** argv) {
  // The per-frame buffers kept in the heap (~6 ms CPU per frame of page faults otherwise): the library's setting.
  amos::api::tuneAllocatorOnce();
  // A reader that goes away (`amos-slam run ... | head -1`) must not kill a run before it writes its outputs: writes
  // to a closed pipe fail with EPIPE instead of raising SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  // Log messages (progress, warnings) go to stderr; stdout carries only the results (summaries, eval figures).
  spdlog::set_default_logger(spdlog::stderr_color_mt("amos"));
  CLI::App app{"Amos-SLAM: RGB-D SLAM for scenes with moving people and objects"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("amos-slam ") + AMOS_VERSION, "Print the version and exit");
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Print debug messages");
  int exit_code = 0;
  amos::app::addRunCommand(app, exit_code);
  amos::app::addEvalCommand(app, exit_code);
  amos::app::addSynthCommand(app, exit_code);
  amos::app::addSegmentCommand(app, exit_code);
  amos::app::addConfigCommand(app, exit_code);
  amos::app::addDiagnoseMoversCommand(app, exit_code);
  amos::app::addVocabCommand(app, exit_code);
  amos::app::addViewCommand(app, exit_code);
  amos::app::addEvalMeshCommand(app, exit_code);
  app.parse_complete_callback([&] { spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info); });
  amos::app::setCommandLine(argc, argv);
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
