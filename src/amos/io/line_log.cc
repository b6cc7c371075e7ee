#include "amos/io/line_log.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "amos/core/error.h"

namespace amos::io {

LineLog::LineLog(std::string path, std::string_view header) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw core::Error(fmt::format("cannot write '{}': {}", path_, std::strerror(errno)));
  append(header);
}

LineLog::~LineLog() {
  if (fd_ >= 0) ::close(fd_);
}

void LineLog::append(std::string_view lines) {
  while (!lines.empty()) {
    const ssize_t n = ::write(fd_, lines.data(), lines.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw core::Error(fmt::format("error while writing '{}': {}", path_, std::strerror(errno)));
    lines.remove_prefix(static_cast<std::size_t>(n));
  }
}

}  // namespace amos::io
