#pragma once
// Where the segmentation models are: the first of --models, the settings file (Segmentation.modelsDir), the
// environment variable AMOS_MODELS, ./models, ../shared/models. A pure function of its sources (the environment
// and the file system are injected) so the order and the error messages are testable.
//
// An explicitly given folder (the first three sources) is used or rejected: if it lacks a required file that is
// an error naming the source, not a silent fall-through to a folder the user did not ask for. The two default
// folders are only tried when nothing was given.
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace amos::segmentation {

using EnvironmentLookup = std::function<std::optional<std::string>(const std::string& name)>;
using FileExists = std::function<bool(const std::string& path)>;

// How the caller's user gives these sources, in the error messages: the command line's words by default; the library
// passes its own (amos::Options' members).
struct SourceNames {
  std::string dir_option = "--models";          // what sets ModelSources::cli_dir
  std::string pass_dir = "Pass --models DIR";   // the advice to give a folder
  std::string modes_without_models = "--mode geometry or --mode none";  // how to run without segmentation
};

struct ModelSources {
  std::string cli_dir;       // --models (empty = not given)
  std::string settings_dir;  // Segmentation.modelsDir from the settings file (empty = not given)
  EnvironmentLookup environment;  // e.g. processEnvironment(); may be empty (= no environment)
  std::vector<std::string> default_dirs = {"./models", "../shared/models"};
  SourceNames names = {};
};

struct ModelLocation {
  std::string dir;     // folder holding every required file
  std::string source;  // where it came from: "--models", "Segmentation.modelsDir", "AMOS_MODELS", "default ./models"
};

// Throws core::Error saying what was tried and what to do (pass --models DIR, set Segmentation.modelsDir or
// AMOS_MODELS, or run without prior-object segmentation: --mode none | geometry), in sources.names' words.
ModelLocation locateModelDir(const ModelSources& sources, const std::vector<std::string>& required_files,
                             const FileExists& exists);
// Same with the real file system.
ModelLocation locateModelDir(const ModelSources& sources, const std::vector<std::string>& required_files);

// The real process environment (std::getenv), for ModelSources::environment.
EnvironmentLookup processEnvironment();

// dir + "/" + file (no separator doubling).
std::string joinPath(const std::string& dir, const std::string& file);

}  // namespace amos::segmentation
