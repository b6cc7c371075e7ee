#include "amos/report/output_folder.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"

namespace amos::report {

namespace fs = std::filesystem;

const std::vector<std::string>& runOutputNames() {
  static const std::vector<std::string> names = {"trajectory.txt", "keyframes.txt", "map.ply",
                                                 "stats.json",     "settings_used.yaml", "masks",
                                                 "overlays",       "report.html"};
  return names;
}

namespace {

// The nearest existing ancestor of `path` (or `path` itself) when it is not a folder: what stops create_directories.
fs::path fileInTheWay(const fs::path& path) {
  std::error_code ec;
  for (fs::path p = path; !p.empty(); p = p.parent_path()) {
    if (fs::exists(p, ec)) return fs::is_directory(p, ec) ? fs::path() : p;
    if (p == p.parent_path()) break;
  }
  return {};
}

void createFolder(const std::string& dir) {
  const fs::path in_the_way = fileInTheWay(dir);
  if (!in_the_way.empty()) {
    throw core::Error(in_the_way == fs::path(dir)
                          ? fmt::format("--output '{}' is a file, not a folder", dir)
                          : fmt::format("cannot create output folder '{}': '{}' is a file", dir, in_the_way.string()));
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw core::Error(fmt::format("cannot create output folder '{}': {}", dir, ec ? ec.message() : "not a folder"));
}

void checkWritable(const std::string& dir) {
  const fs::path probe = fs::path(dir) / fmt::format(".amos-write-test-{}", ::getpid());
  std::FILE* file = std::fopen(probe.c_str(), "wb");
  const bool ok = file != nullptr && std::fputs("amos-slam\n", file) >= 0;
  const int error = errno;
  const bool closed = file != nullptr && std::fclose(file) == 0;
  std::error_code ec;
  fs::remove(probe, ec);
  if (!ok || !closed) {
    throw core::Error(
        fmt::format("cannot write into output folder '{}': {}", dir, std::strerror(ok ? errno : error)));
  }
}

}  // namespace

void prepareOutputFolder(const std::string& dir, bool overwrite) {
  core::require(!dir.empty(), "--output: the output folder must not be empty");
  createFolder(dir);
  std::vector<std::string> earlier;
  for (const std::string& name : runOutputNames()) {
    if (fs::exists(fs::path(dir) / name)) earlier.push_back(name);
  }
  if (!earlier.empty()) {
    if (!overwrite) {
      throw core::Error(fmt::format("output folder '{}' holds an earlier run ({}): give --overwrite to replace it, "
                                    "or another --output",
                                    dir, fmt::join(earlier, ", ")));
    }
    for (const std::string& name : runOutputNames()) {
      const fs::path path = fs::path(dir) / name;
      std::error_code ec;
      fs::remove_all(path, ec);
      if (!ec) fs::remove(io::partialPath(path.string()), ec);
      if (ec) throw core::Error(fmt::format("--overwrite: cannot remove '{}': {}", path.string(), ec.message()));
    }
    spdlog::info("--overwrite: removed the earlier run in {} ({})", dir, fmt::join(earlier, ", "));
  }
  checkWritable(dir);
}

}  // namespace amos::report
