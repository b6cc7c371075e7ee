#include "amos/api/installed_data.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace amos::api {

namespace fs = std::filesystem;

namespace {

// The file (program or shared object) this function's code was loaded from.
fs::path loadedFrom() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&loadedFrom), &info) == 0 || info.dli_fname == nullptr) return {};
  std::error_code error;
  const fs::path path = fs::canonical(info.dli_fname, error);
  return error ? fs::path() : path;
}

bool holdsModels(const fs::path& dir) {
  std::error_code error;
  return fs::is_regular_file(dir / "orb_vocabulary.voc", error) && fs::is_regular_file(dir / "nanodet_m_320.onnx", error);
}

}  // namespace

std::string installedModelsDir() {
  const fs::path file = loadedFrom();
  if (file.empty()) return {};
  // <prefix>/bin/amos-slam, <prefix>/lib/python3/dist-packages/amos_slam*.so
  for (const char* up : {"..", "../../.."}) {
    const fs::path dir = (file.parent_path() / up / "share" / "amos-slam" / "models").lexically_normal();
    if (holdsModels(dir)) return dir.string();
  }
  return {};
}

std::string modelsFolder(const std::string& given, const std::string& settings_dir, const std::string& installed) {
  if (!given.empty()) return given;
  const char* env = std::getenv("AMOS_MODELS");
  if (!settings_dir.empty() || (env != nullptr && *env != 0)) return {};
  return !installed.empty() && holdsModels(installed) ? installed : std::string();
}

}  // namespace amos::api
