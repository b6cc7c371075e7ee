#pragma once
// The socket plumbing of guarded_server.h: a socket closed by its owner, writes that wait a bounded time for room,
// and the httplib::Stream a request is routed from (its screened head) and replied to (the socket).
#include <httplib.h>

#include <chrono>
#include <string>
#include <string_view>

namespace amos::viewer {

// A file descriptor closed by its one owner.
class OwnedSocket {
 public:
  explicit OwnedSocket(int fd = -1) : fd_(fd) {}
  ~OwnedSocket();
  OwnedSocket(OwnedSocket&& other) noexcept;
  OwnedSocket& operator=(OwnedSocket&& other) noexcept;
  OwnedSocket(const OwnedSocket&) = delete;
  OwnedSocket& operator=(const OwnedSocket&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

// True when `fd` can take bytes within `timeout` (0: only if it can now).
bool waitWritable(int fd, std::chrono::milliseconds timeout);
// Sends `data`, each wait for room at most `timeout`; false when it could not all be sent.
bool sendWithin(int fd, std::string_view data, std::chrono::milliseconds timeout);
// Reads and drops whatever a non-blocking pipe holds.
void drainPipe(int fd);

// What httplib reads a request from and writes its reply to: the screened head, then nothing (no request served
// here has a body); the reply goes to the socket, each write waiting at most `write_timeout` for room.
class ReplyStream final : public httplib::Stream {
 public:
  ReplyStream(int fd, std::string head, std::chrono::milliseconds write_timeout)
      : fd_(fd), head_(std::move(head)), write_timeout_(write_timeout) {}
  bool is_readable() const override { return read_ < head_.size(); }
  bool is_writable() const override { return waitWritable(fd_, write_timeout_); }
  ssize_t read(char* ptr, size_t size) override;
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  socket_t socket() const override { return fd_; }
  // A write failed (timed out, or the client went away): the connection is not used again.
  bool failed() const { return failed_; }

 private:
  int fd_;
  std::string head_;
  std::size_t read_ = 0;
  std::chrono::milliseconds write_timeout_;
  bool failed_ = false;
};

}  // namespace amos::viewer
