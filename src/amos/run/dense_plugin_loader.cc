#include "amos/run/dense_plugin_loader.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <mutex>
#include <string>
#include <system_error>

#include "amos/core/error.h"

namespace amos::run {

namespace fs = std::filesystem;

namespace {

std::string lastDlError() {
  const char* error = dlerror();
  return error != nullptr ? error : "unknown error";
}

std::string joined(const std::vector<fs::path>& paths) {
  std::string text;
  for (const fs::path& p : paths) text += (text.empty() ? "" : ", ") + p.string();
  return text;
}

fs::path firstExisting(const std::vector<fs::path>& candidates) {
  for (const fs::path& p : candidates) {
    std::error_code ec;
    if (fs::exists(p, ec)) return p;
  }
  throw core::Error(fmt::format("the dense map's module {} was not found (looked for {}); it is built with "
                                "Open3D (libopen3d-dev) beside amos-slam and installed to lib/amos/",
                                kDensePluginFile, joined(candidates)));
}

fs::path programDir() {
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw core::Error("the dense map's module: cannot read /proc/self/exe: " + ec.message());
  return program.parent_path();
}

}  // namespace

std::vector<fs::path> densePluginCandidates(const fs::path& program_dir) {
  return {program_dir / kDensePluginFile, (program_dir / ".." / "lib" / "amos" / kDensePluginFile).lexically_normal()};
}

void DensePluginLibrary::Closer::operator()(void* handle) const { dlclose(handle); }

DensePluginLibrary::DensePluginLibrary(const std::vector<fs::path>& candidates) : path_(firstExisting(candidates)) {
  // RTLD_LOCAL: the module's symbols (its own copies of core, io...) stay out of the program's lookups.
  // RTLD_NODELETE: dlclose leaves it mapped, because Open3D's OpenMP threads may outlive this object and unloading
  // code they run crashes at exit.
  handle_.reset(dlopen(path_.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE));
  if (!handle_) throw core::Error(fmt::format("cannot load the dense map's module {}: {}", path_.string(), lastDlError()));
  const auto entry = reinterpret_cast<DensePluginEntry>(dlsym(handle_.get(), kDensePluginEntry));
  if (entry == nullptr)
    throw core::Error(fmt::format("the dense map's module {} has no entry point {}: {}", path_.string(),
                                  kDensePluginEntry, lastDlError()));
  DensePluginAbi built_with;
  built_with.version = 0;
  plugin_ = entry(&built_with);
  const DensePluginAbi expected;
  if (!(built_with == expected) || plugin_ == nullptr)
    throw core::Error(fmt::format("the dense map's module {} was built for plugin ABI {} (sizes {} {} {} {} {}), "
                                  "this program needs ABI {} (sizes {} {} {} {} {}): rebuild both from one tree",
                                  path_.string(), built_with.version, built_with.options_size,
                                  built_with.request_size, built_with.score_size, built_with.stage_size,
                                  built_with.info_size, expected.version, expected.options_size,
                                  expected.request_size, expected.score_size, expected.stage_size,
                                  expected.info_size));
}

DensePluginLibrary::~DensePluginLibrary() = default;

const DensePlugin& densePlugin() {
  // Loaded once per process, whichever command asks first; the library is mapped until exit either way
  // (RTLD_NODELETE), so keeping it costs nothing. std::call_once makes a failed load (it throws) leave the flag
  // unset, so the next call tries again and reports the error again.
  static std::once_flag once;
  static std::unique_ptr<DensePluginLibrary> library;
  std::call_once(once, [] { library = std::make_unique<DensePluginLibrary>(densePluginCandidates(programDir())); });
  return library->plugin();
}

}  // namespace amos::run
