#pragma once
// The viewer's embedded HTTP server (Debian's cpp-httplib), read-only, on loopback unless told otherwise:
//   GET /                      the page (index.html; viewer.js, viewer.css beside it)
//   GET /three/three.min.js    three.js from Debian's libjs-three (and /three/OrbitControls.js)
//   GET /api/state             everything the page shows, JSON (LiveState::stateJson); /api/state.js the same as
//                              a script setting window.amosInitialState (the page loads it with itself)
//   GET /api/events?since=SEQ  Server-Sent Events: one "update" per LiveState update after SEQ (delta_json.h);
//                              "reload" when the browser fell too far behind; a comment every second otherwise
//   GET /api/frame.jpg         the current frame with its dynamic mask and keypoints (404 before the first)
//   GET /api/dense/NAME.bin    a dense layer (dense_layer.h: live, mesh, cloud, removed; 404 when there is none)
//   GET /files/PATH            a file of the finished run (`view` only; run_folder.h: anything outside -> 403),
//                              streamed, whole or one byte range (file_reply.h)
// Every request is bounded in the memory, time and threads it can take (guarded_server.h, request_head.h): heads
// are read without holding a thread and within limits, only GET / HEAD without a body and with this server's Host
// are served, a file is streamed and at most one byte range of it is sent, and no handler's exception leaves the
// server. Requests run in the server's own threads (kRequestThreads), which never touch the SLAM run: a slow,
// vanished or hostile client costs only its own connection. An event stream holds its thread while it is open, so
// at most kMaxEventStreams are served at once (more get 503): the other requests always have threads left,
// whatever the number of open tabs. The port is this process's alone: a port in use, by another viewer too, is an
// error at start (no SO_REUSEPORT sharing, which would let two processes listen on it).
#include <atomic>
#include <filesystem>
#include <string>

#include "amos/viewer/guarded_server.h"
#include "amos/viewer/live_state.h"

namespace amos::viewer {

struct ServerOptions {
  std::string bind = "127.0.0.1";  // --viewer-bind
  int port = 8090;                 // --viewer-port; 0 = any free port
  std::filesystem::path run_folder;  // served under /files/ (`view`); empty = no /files/
};

class ViewerServer {
 public:
  static constexpr int kRequestThreads = 20;
  static constexpr int kMaxEventStreams = 12;
  // The limits every connection is held to (ServerLimits' defaults, with kRequestThreads workers).
  static ServerLimits limits();

  // Binds and starts serving; throws core::Error naming the address when it cannot bind.
  ViewerServer(LiveState& state, ServerOptions options);
  ~ViewerServer();
  ViewerServer(const ViewerServer&) = delete;
  ViewerServer& operator=(const ViewerServer&) = delete;

  int port() const { return port_; }
  std::string url() const;
  // Ends the event streams and stops serving (also done by the destructor).
  void stop();

 private:
  void addRoutes();

  LiveState& state_;
  ServerOptions options_;
  std::string three_js_, orbit_controls_js_;
  std::atomic<int> event_streams_{0};
  GuardedServer server_;
  int port_ = 0;
};

}  // namespace amos::viewer
