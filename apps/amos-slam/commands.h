#pragma once
// Each subcommand lives in its own cmd_<name>.cc and registers itself on the root CLI11 app. The callback stores
// the command's exit code in `exit_code`; amos::core::Error thrown by the libraries is reported by main().
#include <CLI/CLI.hpp>

#include <string>

namespace amos::app {

void addRunCommand(CLI::App& app, int& exit_code);
void addEvalCommand(CLI::App& app, int& exit_code);
void addSynthCommand(CLI::App& app, int& exit_code);
void addSegmentCommand(CLI::App& app, int& exit_code);
void addConfigCommand(CLI::App& app, int& exit_code);
void addDiagnoseMoversCommand(CLI::App& app, int& exit_code);
void addVocabCommand(CLI::App& app, int& exit_code);
void addViewCommand(CLI::App& app, int& exit_code);
void addEvalMeshCommand(CLI::App& app, int& exit_code);

// The program's command line, each argument shell-quoted where it needs it (set by main() before parsing; what
// settings_used.yaml records).
void setCommandLine(int argc, char** argv);
const std::string& commandLine();

// A count or an index: a whole number, 0 or more. CLI11 would read "-1" into an unsigned option as 2^64 - 1.
CLI::Validator nonNegativeWhole();
// A TCP port: 0 (any free one) to 65535, instead of the port modulo 65536.
CLI::Validator portNumber();

}  // namespace amos::app
