#pragma once
// Finds and loads the dense plugin (dense_plugin.h), the module built as libamos_dense_plugin.so: beside the
// program (the build tree's bin/), then in ../lib/amos/ from it (an installed package: bin/amos-slam,
// lib/amos/libamos_dense_plugin.so).
#include <filesystem>
#include <memory>
#include <vector>

#include "amos/run/dense_plugin.h"

namespace amos::run {

inline constexpr const char* kDensePluginFile = "libamos_dense_plugin.so";

// Where the module is looked for, in order, for a program in `program_dir`.
std::vector<std::filesystem::path> densePluginCandidates(const std::filesystem::path& program_dir);

// A loaded module and its plugin. The library stays mapped as long as this lives.
class DensePluginLibrary {
 public:
  // The first candidate that exists is loaded. Throws core::Error naming every path tried when none exists, and
  // the path with dlerror() when it cannot be loaded, has no entry point or was built with another ABI.
  explicit DensePluginLibrary(const std::vector<std::filesystem::path>& candidates);
  ~DensePluginLibrary();
  DensePluginLibrary(const DensePluginLibrary&) = delete;
  DensePluginLibrary& operator=(const DensePluginLibrary&) = delete;

  const DensePlugin& plugin() const { return *plugin_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  struct Closer {
    void operator()(void* handle) const;
  };
  std::filesystem::path path_;
  std::unique_ptr<void, Closer> handle_;
  const DensePlugin* plugin_ = nullptr;  // owned by the module (a static object of it)
};

// The plugin for this program (densePluginCandidates of /proc/self/exe's folder), loaded at the first call and kept
// for the process's life. Throws core::Error as DensePluginLibrary does; a later call tries again.
const DensePlugin& densePlugin();

}  // namespace amos::run
