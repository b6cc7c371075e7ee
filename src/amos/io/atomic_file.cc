#include "amos/io/atomic_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "amos/core/error.h"
#include "amos/io/image_codecs.h"

namespace amos::io {

namespace fs = std::filesystem;

std::string partialPath(const std::string& path) { return path + ".partial"; }

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  const std::string partial = partialPath(path);
  std::string error;
  {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(partial.c_str(), "wb"), &std::fclose);
    if (!file) throw core::Error(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file.get()) == bytes.size();
    const int write_errno = errno;
    const bool closed = std::fclose(file.release()) == 0;
    if (!written || !closed) error = std::strerror(written ? errno : write_errno);
  }
  std::error_code ec;
  if (error.empty()) {
    fs::rename(partial, path, ec);
    if (ec) error = ec.message();
  }
  if (!error.empty()) {
    fs::remove(partial, ec);
    throw core::Error(fmt::format("error while writing '{}': {}", path, error));
  }
}

void writeImageAtomically(const std::string& path, const cv::Mat& image) {
  std::vector<std::uint8_t> encoded;
  try {
    encoded = encodeImage(fs::path(path).extension().string(), image);
  } catch (const core::Error& e) {
    throw core::Error(fmt::format("cannot encode '{}': {}", path, e.what()));
  }
  writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

}  // namespace amos::io
