#include "amos/segmentation/model_locator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <filesystem>

#include "amos/core/error.h"

namespace amos::segmentation {
namespace {

std::vector<std::string> missingFiles(const std::string& dir, const std::vector<std::string>& files,
                                      const FileExists& exists) {
  std::vector<std::string> missing;
  for (const auto& f : files)
    if (!exists(joinPath(dir, f))) missing.push_back(f);
  return missing;
}

std::string whatToDo(const std::vector<std::string>& files, const SourceNames& names) {
  return fmt::format(
      "{}, set Segmentation.modelsDir in the settings file or the environment variable AMOS_MODELS to "
      "a folder holding {} (the shared models are in ../shared/models, see its README.md), or run without prior "
      "dynamic object segmentation ({}).",
      names.pass_dir, fmt::join(files, ", "), names.modes_without_models);
}

}  // namespace

std::string joinPath(const std::string& dir, const std::string& file) {
  if (dir.empty()) return file;
  if (dir.back() == '/') return dir + file;
  return dir + "/" + file;
}

ModelLocation locateModelDir(const ModelSources& sources, const std::vector<std::string>& required_files,
                             const FileExists& exists) {
  core::require(!required_files.empty(), "locateModelDir: no model files asked for");
  std::optional<std::string> env_dir;
  if (sources.environment) env_dir = sources.environment("AMOS_MODELS");
  const std::pair<std::string, std::string> explicit_sources[] = {
      {sources.names.dir_option, sources.cli_dir},
      {"Segmentation.modelsDir", sources.settings_dir},
      {"AMOS_MODELS", env_dir.value_or("")}};
  for (const auto& [source, dir] : explicit_sources) {
    if (dir.empty()) continue;
    const auto missing = missingFiles(dir, required_files, exists);
    if (!missing.empty())
      throw core::Error(fmt::format("segmentation models: {} = '{}' does not hold {}. {}", source, dir,
                                    fmt::join(missing, ", "), whatToDo(required_files, sources.names)));
    return {dir, source};
  }
  for (const auto& dir : sources.default_dirs)
    if (missingFiles(dir, required_files, exists).empty()) return {dir, "default " + dir};
  throw core::Error(fmt::format(
      "segmentation models not found: {}, Segmentation.modelsDir and AMOS_MODELS are not set and none of {} "
      "holds {}. {}",
      sources.names.dir_option, fmt::join(sources.default_dirs, ", "), fmt::join(required_files, ", "),
      whatToDo(required_files, sources.names)));
}

ModelLocation locateModelDir(const ModelSources& sources, const std::vector<std::string>& required_files) {
  return locateModelDir(sources, required_files, [](const std::string& path) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
  });
}

EnvironmentLookup processEnvironment() {
  return [](const std::string& name) -> std::optional<std::string> {
    const char* value = std::getenv(name.c_str());
    if (value == nullptr || *value == '\0') return std::nullopt;
    return std::string(value);
  };
}

}  // namespace amos::segmentation
