#include "amos/report/output_folder.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "amos/core/error.h"
#include "amos/core/whole_file.h"
#include "amos/io/atomic_file.h"
#include "amos/report/frame_log.h"

namespace amos::report {

namespace fs = std::filesystem;

const std::vector<std::string>& runOutputNames() {
  static const std::vector<std::string> names = {
      "trajectory.txt", "keyframes.txt", "map.ply",  "stats.json", "settings_used.yaml", "trajectory_live.txt",
      "frames.tsv",     "masks",         "overlays", "report.html", "mesh.ply", "cloud.ply", "removed_points.ply",
      "occupancy.pgm",  "occupancy.yaml"};
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

// Throws `what` + the system's reason when a file cannot be written into `dir`.
void probeWritable(const fs::path& dir, const std::string& what) {
  const fs::path probe = dir / fmt::format(".amos-write-test-{}", ::getpid());
  std::FILE* file = std::fopen(probe.c_str(), "wb");
  const bool ok = file != nullptr && std::fputs("amos-slam\n", file) >= 0;
  const int error = errno;
  const bool closed = file != nullptr && std::fclose(file) == 0;
  std::error_code ec;
  fs::remove(probe, ec);
  if (!ok || !closed) throw core::Error(fmt::format("{}: {}", what, std::strerror(ok ? errno : error)));
}

// `path` absolute with every symlink of its existing part resolved and the rest normalised.
fs::path resolved(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

bool isWithin(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty() && std::next(f) == folder.end()) break;  // a trailing separator
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

// The names an earlier run's manifest lists, each a plain name in the folder (a manifest naming anything else, a
// path with '/' or "..", is refused: --overwrite removes nothing outside the folder).
std::vector<std::string> manifestOutputs(const fs::path& manifest) {
  const nlohmann::json j = nlohmann::json::parse(core::readWholeFile(manifest).value_or(std::string()), nullptr, false);
  const auto bad = [&](const std::string& why) {
    return core::Error(fmt::format("{}: {}; it is not a manifest this program wrote: remove it and the files of that "
                                   "run yourself, or give another --output",
                                   manifest.string(), why));
  };
  if (j.is_discarded() || !j.is_object() || !j.contains("outputs") || !j["outputs"].is_array())
    throw bad("not a run manifest (JSON with \"outputs\": [names])");
  std::vector<std::string> names;
  for (const auto& item : j["outputs"]) {
    if (!item.is_string()) throw bad("an output that is not a name");
    const std::string name = item.get<std::string>();
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
        name == kManifestFile || name == kLockFile)
      throw bad(fmt::format("output '{}' is not a name of a file in the folder", name));
    names.push_back(name);
  }
  return names;
}

// The entries of `dir` but its lock file, names only, sorted.
std::vector<std::string> folderEntries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != kLockFile) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string firstFew(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 5;
  if (names.size() <= kShown) return fmt::format("{}", fmt::join(names, ", "));
  return fmt::format("{}, ... ({} in all)", fmt::join(names.begin(), names.begin() + kShown, ", "), names.size());
}

void removeEarlierRun(const fs::path& dir, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    const fs::path path = dir / name;
    std::error_code ec;
    fs::remove_all(path, ec);
    if (!ec) fs::remove(io::partialPath(path.string()), ec);
    if (ec) throw core::Error(fmt::format("--overwrite: cannot remove '{}': {}", path.string(), ec.message()));
  }
  std::error_code ec;
  fs::remove(dir / kManifestFile, ec);
  if (ec) throw core::Error(fmt::format("--overwrite: cannot remove '{}': {}", (dir / kManifestFile).string(),
                                        ec.message()));
}

// An earlier run is replaced only when its manifest says what it wrote; what no manifest lists is never removed.
void clearEarlierRun(const fs::path& dir, bool overwrite) {
  const fs::path manifest = dir / kManifestFile;
  if (fs::exists(manifest)) {
    const std::vector<std::string> earlier = manifestOutputs(manifest);
    if (!overwrite) {
      throw core::Error(fmt::format("output folder '{}' holds an earlier run ({}): give --overwrite to replace it, "
                                    "or another --output",
                                    dir.string(), firstFew(earlier)));
    }
    removeEarlierRun(dir, earlier);
    spdlog::info("--overwrite: removed the earlier run in {} ({})", dir.string(), firstFew(earlier));
  } else if (overwrite) {
    const std::vector<std::string> foreign = folderEntries(dir);
    if (!foreign.empty()) {
      throw core::Error(fmt::format(
          "--overwrite: output folder '{}' has no run manifest ({}), so nothing in it is known to be written by "
          "amos-slam, and --overwrite removes nothing else: it holds {}. Give a new or empty --output, or move those "
          "files away yourself",
          dir.string(), kManifestFile, firstFew(foreign)));
    }
  }
  std::vector<std::string> in_the_way;
  for (const std::string& name : runOutputNames())
    if (fs::exists(dir / name)) in_the_way.push_back(name);
  if (!in_the_way.empty()) {
    throw core::Error(fmt::format(
        "output folder '{}' holds {}, which no run manifest ({}) lists: not known to be an earlier run's output, so "
        "it is not replaced, even with --overwrite. Move it away, or give another --output",
        dir.string(), firstFew(in_the_way), kManifestFile));
  }
}

}  // namespace

const std::vector<std::string>& mainOutputNames() {
  static const std::vector<std::string> names = {kLiveTrajectoryFile, kFramesFile, "trajectory.txt", "keyframes.txt",
                                                 "map.ply",           "stats.json", "settings_used.yaml"};
  return names;
}

void writeManifest(const std::string& dir, const std::vector<std::string>& outputs) {
  const nlohmann::json j = {
      {"program", "amos-slam"},
      {"about", "what this run writes into this folder; `run --overwrite` removes these, and nothing else"},
      {"pid", static_cast<long>(::getpid())},
      {"outputs", outputs}};
  io::writeFileAtomically((fs::path(dir) / kManifestFile).string(), j.dump(2) + "\n");
}

OutputFolderLock OutputFolderLock::acquire(const std::string& dir) {
  const std::string path = (fs::path(dir) / kLockFile).string();
  for (int attempt = 0; attempt < 10; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      throw core::Error(fmt::format("cannot write into output folder '{}': cannot create its lock file {}: {}", dir,
                                    kLockFile, std::strerror(errno)));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error != EWOULDBLOCK)
        throw core::Error(fmt::format("cannot lock '{}': {}", path, std::strerror(error)));
      std::string holder = core::readWholeFile(path).value_or(std::string());
      holder.erase(std::remove(holder.begin(), holder.end(), '\n'), holder.end());
      throw core::Error(fmt::format("output folder '{}' is in use by another run (PID {}, lock file {}): wait for "
                                    "it to end, or give another --output",
                                    dir, holder.empty() ? "unknown" : holder, path));
    }
    // The holder before may have removed the file between our open and our lock: then lock the new one.
    struct stat opened {}, named {};
    if (::fstat(fd, &opened) != 0 || ::stat(path.c_str(), &named) != 0 || opened.st_ino != named.st_ino ||
        opened.st_dev != named.st_dev) {
      ::close(fd);
      continue;
    }
    std::string previous = core::readWholeFile(path).value_or(std::string());
    previous.erase(std::remove(previous.begin(), previous.end(), '\n'), previous.end());
    if (!previous.empty()) {
      spdlog::warn("output folder {}: taking over the lock left by PID {}, which has ended (a run that was killed)",
                   dir, previous);
    }
    const std::string pid = fmt::format("{}\n", static_cast<long>(::getpid()));
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      const int error = errno;
      ::close(fd);
      throw core::Error(fmt::format("cannot write the lock file '{}': {}", path, std::strerror(error)));
    }
    OutputFolderLock lock;
    lock.path_ = path;
    lock.fd_ = fd;
    return lock;
  }
  throw core::Error(fmt::format("cannot lock '{}': it keeps being replaced by another run", path));
}

OutputFolderLock::~OutputFolderLock() { release(); }

OutputFolderLock::OutputFolderLock(OutputFolderLock&& other) noexcept : path_(std::move(other.path_)), fd_(other.fd_) {
  other.fd_ = -1;
}

OutputFolderLock& OutputFolderLock::operator=(OutputFolderLock&& other) noexcept {
  if (this != &other) {
    release();
    path_ = std::move(other.path_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

// Removed while still locked, so that nobody locks a file that is about to go (acquire() checks the name).
void OutputFolderLock::release() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

void refuseInsideInput(const std::string& path, const std::string& flag, const std::string& input_dir) {
  if (path.empty() || input_dir.empty()) return;
  const fs::path input = resolved(input_dir), output = resolved(path);
  if (!isWithin(output, input)) return;
  throw core::Error(fmt::format("{} '{}' {} the input sequence folder '{}'{}: a run never writes into its input; "
                                "give a path outside it",
                                flag, path, output == input ? "is" : "lies inside", input_dir,
                                output.string() != path || input.string() != input_dir
                                    ? fmt::format(" ({} in {})", output.string(), input.string())
                                    : ""));
}

void checkOutputFile(const std::string& path, const std::string& flag) {
  if (path.empty()) return;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw core::Error(fmt::format("{} '{}' is a folder, not a file", flag, path));
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, ec))
    throw core::Error(fmt::format("{} '{}': its folder '{}' does not exist", flag, path, folder.string()));
  probeWritable(folder, fmt::format("{} '{}': cannot write into its folder '{}'", flag, path, folder.string()));
}

OutputFolderLock prepareOutputFolder(const OutputFolderRequest& request) {
  const std::string& dir = request.dir;
  core::require(!dir.empty(), "--output: the output folder must not be empty");
  refuseInsideInput(dir, "--output", request.input_dir);
  createFolder(dir);
  OutputFolderLock lock = OutputFolderLock::acquire(dir);
  clearEarlierRun(dir, request.overwrite);
  probeWritable(dir, fmt::format("cannot write into output folder '{}'", dir));
  writeManifest(dir, request.outputs);
  return lock;
}

}  // namespace amos::report
