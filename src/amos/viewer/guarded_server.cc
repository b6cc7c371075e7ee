#include "amos/viewer/guarded_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <httplib.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "amos/core/error.h"
#include "amos/core/thread_signals.h"
#include "amos/viewer/socket_io.h"

namespace amos::viewer {
namespace {

using Clock = std::chrono::steady_clock;

// How long a refused connection is kept to read (and drop) what its client still sends, so that closing it does
// not reset the connection before the client has read the refusal.
constexpr std::chrono::milliseconds kLingerTime{1000};
constexpr std::size_t kLingerMaxBytes = 1 << 20;

struct Connection {
  OwnedSocket socket;
  std::string buffer;          // received, not yet handled: a head or the start of one (or of the next one)
  Clock::time_point deadline;  // when waiting for the head (or lingering) ends
  Clock::time_point since;     // when it began waiting: the longest waiting is closed first when too many are open
  int served = 0;              // requests answered on it
  bool head_started = false;   // a byte of the next head has arrived (head_timeout runs from then)
  bool lingering = false;      // refused: reading and dropping until the client closes or kLingerTime ends
  std::size_t dropped = 0;
  bool gone = false;           // handed to a worker or closed: removed from the reception's list
};

// httplib's server without its connection handling: the listening loop hands each accepted socket to `admit`, and
// serve() runs one request read from any Stream (the protected process_request, httplib's routing and replies).
class RoutingCore final : public httplib::Server {
 public:
  std::function<void(int)> admit;
  bool serve(httplib::Stream& stream, bool close, bool& closed, const std::function<void(httplib::Request&)>& setup) {
    return process_request(stream, close, closed, setup);
  }
  // httplib listens with a backlog of 5: connections made while the listening thread waits for a core (a loaded
  // machine, a burst of clients) overflowed it, and each one beyond waited a second for its SYN to be sent again.
  void widenBacklog(int connections) { ::listen(svr_sock_, connections); }

 private:
  bool process_and_close_socket(socket_t sock) override {
    admit(sock);
    return true;
  }
};

// The listening loop's task queue: admitting a connection does not block, so it runs at once in that loop.
class InlineQueue final : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> task) override { task(); }
  void shutdown() override {}
};

}  // namespace

struct GuardedServer::Impl {
  ServerLimits limits;
  HostRule hosts;
  RoutingCore core;
  std::thread listener, reception;
  std::vector<std::thread> workers;
  OwnedSocket wake_read, wake_write;  // a byte written wakes the reception (new or returned connections, stop)

  std::mutex inbox_mutex;
  std::vector<Connection> inbox;  // connections for the reception: accepted, returned after a reply, refused
  bool stopping = false;

  std::mutex jobs_mutex;
  std::condition_variable jobs_ready;
  std::deque<Connection> jobs;  // complete heads waiting for a worker
  bool jobs_closed = false;
  std::atomic<int> at_workers{0};

  std::mutex serving_mutex;
  std::set<int> serving;  // sockets a worker is replying on: shut down by stop() so that no write waits

  explicit Impl(ServerLimits l) : limits(std::move(l)) {}

  void handBack(Connection c);
  void receive();
  void admitArrivals(std::vector<Connection>& waiting, Clock::time_point now);
  void readFrom(Connection& c, Clock::time_point now);
  void advance(Connection& c, Clock::time_point now);
  void refuse(Connection& c, const Refusal& refusal, Clock::time_point now);
  void dispatch(Connection& c, Clock::time_point now);
  void work();
  bool serveOne(Connection& c);
};

void GuardedServer::Impl::handBack(Connection c) {
  {
    std::lock_guard<std::mutex> lock(inbox_mutex);
    if (stopping) return;  // closed here
    inbox.push_back(std::move(c));
  }
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_write.fd(), &byte, 1);  // a full pipe already wakes it
}

void GuardedServer::Impl::refuse(Connection& c, const Refusal& refusal, Clock::time_point now) {
  sendWithin(c.socket.fd(), refusalReply(refusal), std::chrono::milliseconds(0));
  ::shutdown(c.socket.fd(), SHUT_WR);
  c.lingering = true;
  c.buffer.clear();
  c.deadline = now + kLingerTime;
}

void GuardedServer::Impl::dispatch(Connection& c, Clock::time_point now) {
  std::unique_lock<std::mutex> lock(jobs_mutex);
  if (jobs.size() >= static_cast<std::size_t>(limits.max_waiting_requests)) {
    lock.unlock();
    refuse(c, {503, "the viewer is busy: too many requests at once", "Retry-After: 1"}, now);
    return;
  }
  ++at_workers;
  jobs.push_back(std::move(c));
  c.gone = true;
  jobs_ready.notify_one();
}

// What a connection's bytes call for: a worker (a complete head), a refusal (too long), or more waiting.
void GuardedServer::Impl::advance(Connection& c, Clock::time_point now) {
  if (headLength(c.buffer) > 0) return dispatch(c, now);
  if (auto refusal = refuseIncompleteHead(c.buffer, limits.head)) return refuse(c, *refusal, now);
  if (!c.buffer.empty() && !c.head_started) {
    c.head_started = true;
    c.deadline = now + limits.head_timeout;
  }
}

void GuardedServer::Impl::readFrom(Connection& c, Clock::time_point now) {
  char chunk[4096];
  // At most one byte beyond the head limit is kept: enough to see that it is exceeded.
  const std::size_t room = c.lingering ? sizeof(chunk) : std::min(sizeof(chunk), limits.head.max_head + 1 - c.buffer.size());
  const ssize_t n = ::recv(c.socket.fd(), chunk, room, MSG_DONTWAIT);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
  if (n <= 0) {
    c.gone = true;  // the client closed (or reset) the connection
  } else if (c.lingering) {
    c.dropped += static_cast<std::size_t>(n);
    c.gone = c.dropped > kLingerMaxBytes;
  } else {
    c.buffer.append(chunk, static_cast<std::size_t>(n));
    advance(c, now);
  }
}

void GuardedServer::Impl::admitArrivals(std::vector<Connection>& waiting, Clock::time_point now) {
  std::vector<Connection> arrived;
  {
    std::lock_guard<std::mutex> lock(inbox_mutex);
    arrived.swap(inbox);
  }
  for (Connection& c : arrived) {
    c.since = now;
    c.head_started = !c.buffer.empty();
    if (!c.lingering) c.deadline = now + (c.head_started ? limits.head_timeout : limits.idle_timeout);
    waiting.push_back(std::move(c));
    if (!waiting.back().lingering) advance(waiting.back(), now);  // a returned connection may hold the next head
  }
  // Too many open: the one waiting longest for its head makes room (slow or idle clients cannot keep new ones out).
  const auto open = [&] {
    return at_workers.load() + std::count_if(waiting.begin(), waiting.end(), [](const Connection& c) { return !c.gone; });
  };
  while (open() > limits.max_connections) {
    auto oldest = waiting.end();
    for (auto it = waiting.begin(); it != waiting.end(); ++it)
      if (!it->gone && (oldest == waiting.end() || it->since < oldest->since)) oldest = it;
    if (oldest == waiting.end()) break;
    if (oldest->lingering || oldest->buffer.empty()) {
      oldest->gone = true;
    } else {
      refuse(*oldest, {503, "too many open connections", "Retry-After: 1"}, now);
      oldest->gone = true;
    }
  }
}

void GuardedServer::Impl::receive() {
  std::vector<Connection> waiting;
  std::vector<pollfd> polled;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(inbox_mutex);
      if (stopping) break;
    }
    admitArrivals(waiting, Clock::now());
    waiting.erase(std::remove_if(waiting.begin(), waiting.end(), [](const Connection& c) { return c.gone; }),
                  waiting.end());
    polled.assign(1, pollfd{wake_read.fd(), POLLIN, 0});
    Clock::time_point next = Clock::now() + limits.idle_timeout;
    for (const Connection& c : waiting) {
      polled.push_back(pollfd{c.socket.fd(), POLLIN, 0});
      next = std::min(next, c.deadline);
    }
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now()).count() + 1;
    ::poll(polled.data(), polled.size(), static_cast<int>(std::max<long long>(wait, 0)));
    if (polled[0].revents != 0) drainPipe(wake_read.fd());
    const Clock::time_point now = Clock::now();
    for (std::size_t i = 0; i < waiting.size(); ++i) {
      Connection& c = waiting[i];
      if (polled[i + 1].revents != 0) readFrom(c, now);
      if (c.gone || c.deadline > now) continue;
      if (c.lingering || c.buffer.empty())
        c.gone = true;  // an idle kept-alive connection, or a refused one that had its time
      else
        refuse(c, {408, fmt::format("request head not complete within {} ms", limits.head_timeout.count()), {}}, now);
    }
    waiting.erase(std::remove_if(waiting.begin(), waiting.end(), [](const Connection& c) { return c.gone; }),
                  waiting.end());
  }
}

// One request: screened, then routed by httplib; true when its connection may carry another.
bool GuardedServer::Impl::serveOne(Connection& c) {
  const std::size_t length = headLength(c.buffer);
  const ScreenedHead screened = screenHead(std::string_view(c.buffer).substr(0, length), hosts, limits.head);
  c.buffer.erase(0, length);
  if (screened.refusal) {
    sendWithin(c.socket.fd(), refusalReply(*screened.refusal), limits.write_timeout);
    ::shutdown(c.socket.fd(), SHUT_WR);
    c.lingering = true;
    c.buffer.clear();
    c.deadline = Clock::now() + kLingerTime;
    return true;  // to the reception, which drops what the client still sends
  }
  ++c.served;
  {
    std::lock_guard<std::mutex> lock(serving_mutex);
    serving.insert(c.socket.fd());
  }
  ReplyStream stream(c.socket.fd(), screened.forwarded, limits.write_timeout);
  bool closed = false, ok = false;
  try {
    ok = core.serve(stream, c.served >= limits.max_requests_per_connection, closed, [&](httplib::Request& req) {
      if (!screened.range.empty()) req.set_header("Range", screened.range);
    });
  } catch (const std::exception& e) {
    spdlog::warn("viewer: a request ended by an error (its connection is closed): {}", e.what());
  } catch (...) {
    spdlog::warn("viewer: a request ended by an unknown error (its connection is closed)");
  }
  {
    std::lock_guard<std::mutex> lock(serving_mutex);
    serving.erase(c.socket.fd());
  }
  return ok && !closed && !stream.failed() && c.served < limits.max_requests_per_connection;
}

void GuardedServer::Impl::work() {
  for (;;) {
    Connection c;
    {
      std::unique_lock<std::mutex> lock(jobs_mutex);
      jobs_ready.wait(lock, [&] { return jobs_closed || !jobs.empty(); });
      if (jobs.empty()) return;
      c = std::move(jobs.front());
      jobs.pop_front();
    }
    const bool keep = serveOne(c);
    --at_workers;
    if (keep) handBack(std::move(c));  // else closed here
  }
}

GuardedServer::GuardedServer(ServerLimits limits) : impl_(std::make_unique<Impl>(std::move(limits))) {
  RoutingCore& core = impl_->core;
  core.new_task_queue = [] { return new InlineQueue(); };
  core.admit = [impl = impl_.get()](int fd) {
    Connection c;
    c.socket = OwnedSocket(fd);
    impl->handBack(std::move(c));
  };
  // SO_REUSEADDR only (a port in TIME_WAIT can be bound again), not httplib's default SO_REUSEPORT, with which a
  // second process binds a port in use and the two share its connections.
  core.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<void*>(&yes), sizeof(yes));
  });
  // Only for the Keep-Alive header httplib writes: the limits themselves are kept here.
  core.set_keep_alive_max_count(static_cast<std::size_t>(impl_->limits.max_requests_per_connection));
  core.set_keep_alive_timeout(
      std::max<time_t>(1, std::chrono::duration_cast<std::chrono::seconds>(impl_->limits.idle_timeout).count()));
  core.set_exception_handler([](const httplib::Request& req, httplib::Response& res, std::exception_ptr error) {
    std::string what = "unknown error";
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    spdlog::warn("viewer: {} {} failed: {}", req.method, req.path.substr(0, 200), what);
    res.status = 500;
    res.set_content("internal error\n", "text/plain");
  });
}

GuardedServer::~GuardedServer() { stop(); }

httplib::Server& GuardedServer::routes() { return impl_->core; }

int GuardedServer::listen(const std::string& bind, int port) {
  Impl& impl = *impl_;
  const int bound = port == 0 ? impl.core.bind_to_any_port(bind) : (impl.core.bind_to_port(bind, port) ? port : -1);
  core::require(bound > 0, fmt::format("viewer: cannot listen on {}:{}: port {} is in use (or {} is not an address "
                                       "of this machine); choose another with --viewer-port / --viewer-bind",
                                       bind, port, port, bind));
  impl.hosts = HostRule{bind, bound};
  impl.core.widenBacklog(impl.limits.max_connections);
  int pipe_fds[2];
  core::require(::pipe2(pipe_fds, O_NONBLOCK | O_CLOEXEC) == 0, "viewer: cannot create a pipe");
  impl.wake_read = OwnedSocket(pipe_fds[0]);
  impl.wake_write = OwnedSocket(pipe_fds[1]);
  impl.listener = std::thread([&impl] {
    // Every thread of the server starts from here and inherits this mask: SIGINT / SIGTERM stay with the main thread.
    core::blockTerminationSignalsInThisThread();
    impl.reception = std::thread([&impl] { impl.receive(); });
    for (int i = 0; i < impl.limits.workers; ++i) impl.workers.emplace_back([&impl] { impl.work(); });
    impl.core.listen_after_bind();
  });
  // httplib 0.11's stop() does nothing before the listening loop has started, and the loop then never ends: a
  // server stopped at once (a run that fails before its first frame, a test) would hang its destructor. The library
  // gives no signal for the start, so wait here (briefly: it is the next thing that thread does) until it runs.
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  while (!impl.core.is_running() && Clock::now() < deadline) std::this_thread::yield();
  return bound;
}

void GuardedServer::stop() {
  Impl& impl = *impl_;
  if (!impl.listener.joinable()) return;
  impl.core.stop();
  impl.listener.join();
  {
    std::lock_guard<std::mutex> lock(impl.inbox_mutex);
    impl.stopping = true;
  }
  const char byte = 1;
  [[maybe_unused]] const ssize_t n = ::write(impl.wake_write.fd(), &byte, 1);  // wakes the reception
  impl.reception.join();
  {
    std::lock_guard<std::mutex> lock(impl.jobs_mutex);
    impl.jobs_closed = true;
    impl.jobs.clear();
  }
  impl.jobs_ready.notify_all();
  {
    std::lock_guard<std::mutex> lock(impl.serving_mutex);
    for (const int fd : impl.serving) ::shutdown(fd, SHUT_RDWR);
  }
  for (std::thread& t : impl.workers) t.join();
  impl.workers.clear();
}

}  // namespace amos::viewer
