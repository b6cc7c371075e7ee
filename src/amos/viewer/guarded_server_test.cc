#include "amos/viewer/guarded_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <stdexcept>

#include "amos/viewer/raw_http_client.h"

namespace amos::viewer {
namespace {

using std::chrono::milliseconds;
using testing::RawConnection;
using testing::statusOf;

ServerLimits quickLimits() {
  ServerLimits limits;
  limits.workers = 2;
  limits.head_timeout = milliseconds(300);
  limits.idle_timeout = milliseconds(300);
  limits.max_requests_per_connection = 3;
  return limits;
}

struct GuardedServed {
  GuardedServer server;
  int port = 0;
  explicit GuardedServed(ServerLimits limits = quickLimits()) : server(limits) {
    server.routes().Get("/ok", [](const httplib::Request&, httplib::Response& res) { res.set_content("ok", "text/plain"); });
    server.routes().Get("/throws", [](const httplib::Request&, httplib::Response&) { throw std::runtime_error("boom"); });
    server.routes().Get("/throws-int", [](const httplib::Request&, httplib::Response&) { throw 42; });
    // Throws while the reply is written, outside httplib's own try (which ended the process).
    server.routes().Get("/throws-later", [](const httplib::Request&, httplib::Response& res) {
      res.set_chunked_content_provider("text/plain", [](std::size_t, httplib::DataSink&) -> bool {
        throw std::runtime_error("boom while writing");
      });
    });
    port = server.listen("127.0.0.1", 0);
  }
  std::string request(const std::string& path, bool close = true) const {
    return "GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n" +
           (close ? "Connection: close\r\n" : "") + "\r\n";
  }
};

TEST(GuardedServer, AHandlerThatThrowsGets500AndTheServerGoesOn) {
  GuardedServed s;
  EXPECT_EQ(statusOf(testing::roundTrip(s.port, s.request("/throws"))), 500);
  EXPECT_EQ(statusOf(testing::roundTrip(s.port, s.request("/throws-int"))), 500);
  const std::string later = testing::roundTrip(s.port, s.request("/throws-later"));
  EXPECT_TRUE(statusOf(later) == 200 || statusOf(later) == 0) << later;  // the head may be out: then it just ends
  EXPECT_EQ(statusOf(testing::roundTrip(s.port, s.request("/ok"))), 200);
}

TEST(GuardedServer, AHeadNotCompleteInTimeIs408) {
  GuardedServed s;
  RawConnection c(s.port);
  c.send("GET /ok HTTP/1.1\r\n");
  const auto start = std::chrono::steady_clock::now();
  const std::string reply = c.readUntilClosed(milliseconds(3000));
  EXPECT_EQ(statusOf(reply), 408) << reply;
  EXPECT_LT(std::chrono::steady_clock::now() - start, milliseconds(1500));
}

// Keep-alive abuse: an idle kept-alive connection is closed, and a connection carries a bounded number of requests.
TEST(GuardedServer, KeptAliveConnectionsAreBounded) {
  GuardedServed s;
  RawConnection idle(s.port);
  idle.send(s.request("/ok", false));
  const auto start = std::chrono::steady_clock::now();
  const std::string reply = idle.readUntilClosed(milliseconds(3000));
  EXPECT_EQ(statusOf(reply), 200);
  EXPECT_TRUE(idle.closedByServer());
  EXPECT_LT(std::chrono::steady_clock::now() - start, milliseconds(1500));

  RawConnection busy(s.port);
  std::string five;
  for (int i = 0; i < 5; ++i) five += s.request("/ok", false);
  busy.send(five);
  const std::string replies = busy.readUntilClosed(milliseconds(3000));
  std::size_t count = 0;
  for (std::size_t at = replies.find("HTTP/1.1 200"); at != std::string::npos; at = replies.find("HTTP/1.1 200", at + 1))
    ++count;
  EXPECT_EQ(count, 3u) << replies;
}

// More connections than allowed: the one waiting longest for its head is closed to make room for the newest.
TEST(GuardedServer, TheLongestWaitingConnectionMakesRoom) {
  ServerLimits limits = quickLimits();
  limits.max_connections = 4;
  limits.head_timeout = limits.idle_timeout = milliseconds(10000);
  GuardedServed s(limits);
  RawConnection first(s.port);
  first.send("GET /ok HTTP/1.1\r\n");
  std::vector<std::unique_ptr<RawConnection>> others;
  for (int i = 0; i < 4; ++i) {
    others.push_back(std::make_unique<RawConnection>(s.port));
    std::this_thread::sleep_for(milliseconds(20));
  }
  const std::string evicted = first.readUntilClosed(milliseconds(2000));
  EXPECT_EQ(statusOf(evicted), 503) << evicted;
  EXPECT_TRUE(first.closedByServer());
  EXPECT_EQ(statusOf(testing::roundTrip(s.port, s.request("/ok"))), 200);
}

TEST(GuardedServer, StopsWithConnectionsOpen) {
  auto s = std::make_unique<GuardedServed>();
  RawConnection idle(s->port), partial(s->port);
  partial.send("GET /ok HTTP/1.1\r\n");
  const auto start = std::chrono::steady_clock::now();
  s.reset();
  EXPECT_LT(std::chrono::steady_clock::now() - start, milliseconds(1000));
}

}  // namespace
}  // namespace amos::viewer
