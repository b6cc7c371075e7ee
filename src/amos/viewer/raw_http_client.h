#pragma once
// Test helper: a raw TCP client for the viewer server's tests, which send what no HTTP library would (hundreds of
// ranges, endless lines, slow heads, bodies to a read-only server) and look at the bytes that come back.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstddef>
#include <fstream>
#include <string>
#include <string_view>

namespace amos::viewer::testing {

class RawConnection {
 public:
  explicit RawConnection(int port) : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
    if (connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) close();
  }
  ~RawConnection() { close(); }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return fd_ >= 0; }
  // False when not all could be sent (the server closed the connection).
  bool send(std::string_view data) {
    while (!data.empty() && fd_ >= 0) {
      const ssize_t n = ::send(fd_, data.data(), data.size(), MSG_NOSIGNAL);
      if (n <= 0) return false;
      data.remove_prefix(static_cast<std::size_t>(n));
    }
    return data.empty();
  }
  // What arrives until the server closes the connection, `timeout` passes or `keep` bytes were kept (bytes beyond
  // are counted in received() and dropped).
  std::string readUntilClosed(std::chrono::milliseconds timeout, std::size_t keep = 1 << 20) {
    std::string out;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    char chunk[65536];
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      pollfd p{fd_, POLLIN, 0};
      if (left.count() <= 0 || poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
      const ssize_t n = recv(fd_, chunk, sizeof(chunk), 0);
      if (n <= 0) {
        closed_by_server_ = true;
        break;
      }
      received_ += static_cast<std::size_t>(n);
      if (out.size() < keep) out.append(chunk, std::min(static_cast<std::size_t>(n), keep - out.size()));
    }
    return out;
  }
  std::size_t received() const { return received_; }
  bool closedByServer() const { return closed_by_server_; }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
  std::size_t received_ = 0;
  bool closed_by_server_ = false;
};

// The status of a reply ("HTTP/1.1 421 ..." -> 421), 0 when there is none.
inline int statusOf(std::string_view reply) {
  if (reply.size() < 12 || reply.substr(0, 5) != "HTTP/") return 0;
  return std::atoi(std::string(reply.substr(9, 3)).c_str());
}

// The body of a reply (after its head), empty when there is none.
inline std::string bodyOf(const std::string& reply) {
  const std::size_t end = reply.find("\r\n\r\n");
  return end == std::string::npos ? std::string() : reply.substr(end + 4);
}

// One request on its own connection; the reply as far as it came within `timeout`.
inline std::string roundTrip(int port, std::string_view request,
                            std::chrono::milliseconds timeout = std::chrono::milliseconds(3000)) {
  RawConnection c(port);
  c.send(request);
  return c.readUntilClosed(timeout);
}

inline std::string get(int port, const std::string& path, const std::string& extra_headers = {}) {
  return roundTrip(port, "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                            "\r\nConnection: close\r\n" + extra_headers + "\r\n");
}

// This process's peak resident memory so far in bytes (VmHWM).
inline std::size_t peakResidentBytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  std::size_t kb = 0;
  while (status >> key) {
    if (key == "VmHWM:" && status >> kb) return kb * 1024;
    status.ignore(1 << 10, '\n');
  }
  return 0;
}

}  // namespace amos::viewer::testing
