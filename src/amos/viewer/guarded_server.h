#pragma once
// An HTTP server in which every request is bounded in the memory, time and threads it can take, whatever a client
// sends or fails to send. cpp-httplib routes the requests and runs the handlers; the connections are this server's:
//   - one reception thread reads every connection's request head without blocking (poll), within
//     ServerLimits::head_timeout and the size limits of request_head.h, so slow or idle clients (slowloris, idle
//     keep-alive connections) hold no thread; a head that passed screenHead() goes to a worker;
//   - ServerLimits::workers threads serve the requests; at most max_waiting_requests heads wait for one, beyond
//     that the request gets 503 at once;
//   - at most max_connections are open: a new connection beyond it closes the one that has waited longest for its
//     head (one that is being served is never closed), or gets 503 when all are being served;
//   - a reply that cannot be written for write_timeout ends its connection; no exception of a handler or of
//     httplib leaves a worker (the request gets 500, or its connection is closed).
// Refused requests get a short reply naming the reason (refusalReply) and their connection is closed after it.
#include <chrono>
#include <memory>
#include <string>

#include "amos/viewer/request_head.h"

namespace httplib {
class Server;
}

namespace amos::viewer {

struct ServerLimits {
  int workers = 20;                 // requests served at once (an open event stream holds one while it is open)
  int max_connections = 256;        // open connections
  int max_waiting_requests = 64;    // complete heads waiting for a worker
  int max_requests_per_connection = 100;
  std::chrono::milliseconds head_timeout{5000};   // from a request's first byte to its blank line (then 408)
  std::chrono::milliseconds idle_timeout{5000};   // a kept-alive connection without a new request is closed
  std::chrono::milliseconds write_timeout{5000};  // a reply that makes no progress for this long is abandoned
  HeadLimits head;
};

class GuardedServer {
 public:
  explicit GuardedServer(ServerLimits limits = {});
  ~GuardedServer();
  GuardedServer(const GuardedServer&) = delete;
  GuardedServer& operator=(const GuardedServer&) = delete;

  // Where the handlers are added, before listen().
  httplib::Server& routes();
  // Binds `bind`:`port` (0: any free port) and serves in background threads, whose signals SIGINT / SIGTERM are
  // blocked (they stay with the main thread). Returns the port; throws core::Error when it cannot bind.
  int listen(const std::string& bind, int port);
  // Stops serving: closes every connection and joins the threads (also done by the destructor).
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos::viewer
