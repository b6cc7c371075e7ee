#pragma once
// A text file written as it grows, for what must survive any end of the program (SIGKILL, a power cut of the
// process, a crash): each append() is one write(2) of whole lines, straight to the operating system (no buffer in
// this process), so the file holds every line appended before the end and never a part of one. (Not fsync'ed: the
// lines survive the process, not the machine.) Cost: one small system call per append.
#include <string>
#include <string_view>

namespace amos::io {

class LineLog {
 public:
  // Creates `path` (replacing a file there) and writes `header` (whole lines). Throws core::Error naming the file
  // when it cannot.
  LineLog(std::string path, std::string_view header);
  ~LineLog();
  LineLog(const LineLog&) = delete;
  LineLog& operator=(const LineLog&) = delete;

  // Appends `lines` (whole lines, each ending in '\n'). Throws core::Error naming the file when it cannot (a full
  // disk): the file then still ends with a whole line or with the part this call wrote of one.
  void append(std::string_view lines);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace amos::io
