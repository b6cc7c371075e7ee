// The viewer's server against hostile requests (issue 51): each one is answered within bounds of memory, time and
// threads, or refused with a short reason, and the server keeps serving /api/state meanwhile.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>
#include <vector>

#include "amos/testing/scratch_dir.h"
#include "amos/viewer/http_server.h"
#include "amos/viewer/raw_http_client.h"

namespace amos::viewer {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using testing::RawConnection;
using testing::statusOf;

constexpr std::size_t kFileBytes = 512 * 1024;

struct HostileServed {
  fs::path run;
  LiveState state;
  std::unique_ptr<ViewerServer> server;
  int port() const { return server->port(); }
  std::string host() const { return "Host: 127.0.0.1:" + std::to_string(port()) + "\r\n"; }
};

std::unique_ptr<HostileServed> serveHostile() {
  auto s = std::make_unique<HostileServed>();
  const fs::path parent = amos::testing::scratchDirForThisTest("viewer_hostile_");
  s->run = parent / "run";
  fs::create_directories(s->run);
  std::string bytes(kFileBytes, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>('a' + i % 26);
  std::ofstream(s->run / "file.bin", std::ios::binary) << bytes;
  std::ofstream(parent / "secret.txt") << "SECRET";
  ServerOptions options;
  options.port = 0;
  options.run_folder = s->run;
  s->server = std::make_unique<ViewerServer>(s->state, options);
  return s;
}

// The time /api/state takes to answer (its status in `status`).
milliseconds timeState(int port, int& status) {
  const auto start = std::chrono::steady_clock::now();
  status = statusOf(testing::get(port, "/api/state"));
  return std::chrono::duration_cast<milliseconds>(std::chrono::steady_clock::now() - start);
}

std::string manyRanges(int count) {
  std::string ranges = "Range: bytes=0-";
  for (int i = 1; i < count; ++i) ranges += ",0-";
  return ranges + "\r\n";
}

// Hundreds of ranges once made a reply of hundreds of copies of the file (gigabytes: std::bad_alloc ended the
// process). Now a list of ranges is ignored: the whole file, once; the process memory stays small.
TEST(ViewerServerHostile, HundredsOfRangesGetTheFileOnce) {
  const auto s = serveHostile();
  const std::size_t before = testing::peakResidentBytes();
  for (const char* path : {"/files/file.bin", "/api/state", "/"}) {
    RawConnection c(s->port());
    c.send(std::string("GET ") + path + " HTTP/1.1\r\n" + s->host() + manyRanges(400) + "Connection: close\r\n\r\n");
    const std::string reply = c.readUntilClosed(milliseconds(5000), 4096);
    EXPECT_EQ(statusOf(reply), 200) << path;
    EXPECT_LE(c.received(), kFileBytes + 4096) << path;
    EXPECT_TRUE(c.closedByServer()) << path;
  }
  EXPECT_LT(testing::peakResidentBytes(), before + (64u << 20));
}

TEST(ViewerServerHostile, OneRangeIsServedAndAnUnsatisfiableOneIs416) {
  const auto s = serveHostile();
  std::string reply = testing::get(s->port(), "/files/file.bin", "Range: bytes=26-30\r\n");
  EXPECT_EQ(statusOf(reply), 206) << reply;
  EXPECT_EQ(testing::bodyOf(reply), "abcde");
  EXPECT_NE(reply.find("Content-Range: bytes 26-30/" + std::to_string(kFileBytes)), std::string::npos) << reply;
  reply = testing::get(s->port(), "/files/file.bin", "Range: bytes=-3\r\n");
  EXPECT_EQ(statusOf(reply), 206);
  EXPECT_EQ(testing::bodyOf(reply).size(), 3u);
  reply = testing::get(s->port(), "/files/file.bin", "Range: bytes=" + std::to_string(kFileBytes) + "-\r\n");
  EXPECT_EQ(statusOf(reply), 416) << reply;
  EXPECT_NE(reply.find("Content-Range: bytes */" + std::to_string(kFileBytes)), std::string::npos) << reply;
}

// A file is streamed from disk: serving a large one costs the process pieces of it, not the whole file (it was
// read into memory, and copied, for each request).
TEST(ViewerServerHostile, ALargeFileIsStreamedNotLoaded) {
  const auto s = serveHostile();
  const std::uintmax_t large = 256u << 20;
  fs::resize_file(s->run / "file.bin", large);  // sparse: fast to write and to read
  const std::size_t before = testing::peakResidentBytes();
  RawConnection c(s->port());
  c.send("GET /files/file.bin HTTP/1.1\r\n" + s->host() + "Connection: close\r\n\r\n");
  c.readUntilClosed(milliseconds(30000), 0);  // counted, not kept
  EXPECT_TRUE(c.closedByServer());
  EXPECT_GT(c.received(), large);
  EXPECT_LT(testing::peakResidentBytes(), before + (64u << 20));
}

// DNS rebinding: a page of another site reaches 127.0.0.1 under its own name; the Host header shows it.
TEST(ViewerServerHostile, AForeignHostIsRefused) {
  const auto s = serveHostile();
  const std::string port = std::to_string(s->port());
  for (const std::string& host :
       std::vector<std::string>{"evil.example:" + port, "evil.example", "127.0.0.1:1", "localhost.evil.example:" + port}) {
    const std::string reply = testing::roundTrip(s->port(), "GET /api/state HTTP/1.1\r\nHost: " + host + "\r\n\r\n");
    EXPECT_EQ(statusOf(reply), 421) << host << "\n" << reply;
    EXPECT_EQ(reply.find("\"points\""), std::string::npos) << host;
  }
  for (const std::string& host :
       std::vector<std::string>{"127.0.0.1:" + port, "localhost:" + port, "LOCALHOST:" + port, "[::1]:" + port}) {
    const std::string reply =
        testing::roundTrip(s->port(), "GET /api/state HTTP/1.1\r\nHost: " + host + "\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(statusOf(reply), 200) << host << "\n" << reply;
  }
  EXPECT_EQ(statusOf(testing::roundTrip(s->port(), "GET /api/state HTTP/1.1\r\n\r\n")), 400);  // no Host at all
}

// Thirty-odd connections sending their heads a byte at a time held the request threads: /api/state waited
// seconds. Heads are now read without a thread, so it answers at once.
TEST(ViewerServerHostile, SlowHeadsDoNotStallTheState) {
  const auto s = serveHostile();
  std::vector<std::unique_ptr<RawConnection>> slow;
  for (int i = 0; i < 40; ++i) {
    slow.push_back(std::make_unique<RawConnection>(s->port()));
    slow.back()->send("GET /api/state HTTP/1.1\r\n");
  }
  for (int round = 0; round < 4; ++round) {
    for (auto& c : slow) c->send("X");  // a byte now and then: no read ever times out
    int status = 0;
    EXPECT_LT(timeState(s->port(), status).count(), 1000) << "round " << round;
    EXPECT_EQ(status, 200);
    std::this_thread::sleep_for(milliseconds(700));
  }
}

// Idle connections (opened, nothing sent) beyond the limit make room: the one waiting longest is closed, and a
// new request is served at once instead of queueing behind them.
TEST(ViewerServerHostile, ManyIdleConnectionsDoNotKeepRequestsOut) {
  const auto s = serveHostile();
  std::vector<std::unique_ptr<RawConnection>> idle;
  for (int i = 0; i < 300; ++i)  // beyond the limit of open connections (256)
    idle.push_back(std::make_unique<RawConnection>(s->port()));
  int status = 0;
  EXPECT_LT(timeState(s->port(), status).count(), 1000);
  EXPECT_EQ(status, 200);
}

// A line without end grew the server's buffer without bound (and held a thread while it came); it is refused
// once it is longer than the limit.
TEST(ViewerServerHostile, AnEndlessRequestLineIs414) {
  const auto s = serveHostile();
  RawConnection c(s->port());
  c.send("GET /" + std::string(100000, 'a'));
  const std::string reply = c.readUntilClosed(milliseconds(2000));
  EXPECT_EQ(statusOf(reply), 414) << reply.substr(0, 200);
  EXPECT_TRUE(c.closedByServer());
}

// The longest target allowed goes through httplib's routing regular expressions (recursive in libstdc++) safely.
TEST(ViewerServerHostile, TheLongestTargetIsRoutedSafely) {
  const auto s = serveHostile();
  const std::size_t room = 4096 - std::string("GET  HTTP/1.1").size();  // the longest request line allowed
  for (const std::string prefix : {"/files/", "/api/dense/", "/"}) {
    const std::string path = prefix + std::string(room - prefix.size() - 4, 'a') + ".bin";
    const int status = statusOf(testing::get(s->port(), path));
    EXPECT_TRUE(status == 403 || status == 404) << prefix << " " << status;
  }
  int status = 0;
  timeState(s->port(), status);
  EXPECT_EQ(status, 200);
}

TEST(ViewerServerHostile, TooManyOrTooLongHeadersAre431) {
  const auto s = serveHostile();
  std::string many;
  for (int i = 0; i < 1000; ++i) many += "X-Header-" + std::to_string(i) + ": x\r\n";
  EXPECT_EQ(statusOf(testing::roundTrip(s->port(), "GET /api/state HTTP/1.1\r\n" + s->host() + many + "\r\n")), 431);
  const std::string long_header = "X-Long: " + std::string(40000, 'x') + "\r\n";
  EXPECT_EQ(statusOf(testing::roundTrip(s->port(), "GET /api/state HTTP/1.1\r\n" + s->host() + long_header + "\r\n")),
            431);
}

TEST(ViewerServerHostile, OtherMethodsThanGetAndHeadAre405) {
  const auto s = serveHostile();
  for (const char* method : {"POST", "PUT", "DELETE", "PATCH", "OPTIONS", "TRACE", "CONNECT"}) {
    const std::string reply =
        testing::roundTrip(s->port(), std::string(method) + " /api/state HTTP/1.1\r\n" + s->host() + "\r\n");
    EXPECT_EQ(statusOf(reply), 405) << method;
    EXPECT_NE(reply.find("Allow: GET, HEAD"), std::string::npos) << method;
  }
  const std::string head = testing::roundTrip(s->port(), "HEAD /api/state HTTP/1.1\r\n" + s->host() + "Connection: close\r\n\r\n");
  EXPECT_EQ(statusOf(head), 200);
}

// A body (announced large, or chunked and never ending) is refused at once, without reading it: 405 for a method
// other than GET (the server is read-only), 413 for a GET with a body.
TEST(ViewerServerHostile, ABodyIsRefusedUnread) {
  const auto s = serveHostile();
  for (const std::string framing : {"Content-Length: 1000000000\r\n", "Transfer-Encoding: chunked\r\n"}) {
    for (const char* method : {"POST", "GET"}) {
      RawConnection c(s->port());
      const auto start = std::chrono::steady_clock::now();
      c.send(std::string(method) + " /api/state HTTP/1.1\r\n" + s->host() + framing + "\r\n" + std::string(1000, 'b'));
      const std::string reply = c.readUntilClosed(milliseconds(3000));
      EXPECT_EQ(statusOf(reply), std::string(method) == "GET" ? 413 : 405) << method << " " << framing;
      EXPECT_LT(std::chrono::steady_clock::now() - start, milliseconds(1500)) << method << " " << framing;
    }
  }
}

// Path tricks on /files/: a link out of the run, an encoded NUL, encoded '..', a FIFO.
TEST(ViewerServerHostile, PathTricksAreRefused) {
  const auto s = serveHostile();
  fs::create_symlink(s->run.parent_path() / "secret.txt", s->run / "link.txt");
  fs::create_directory_symlink(s->run.parent_path(), s->run / "up");
  for (const char* path : {"/files/link.txt", "/files/up/secret.txt", "/files/file.bin%00.txt", "/files/%2e%2e/secret.txt",
                           "/files/.%2e/secret.txt", "/files/%252e%252e/secret.txt", "/files/file.bin/..%2f..%2fsecret.txt"}) {
    const std::string reply = testing::get(s->port(), path);
    EXPECT_TRUE(statusOf(reply) == 400 || statusOf(reply) == 403 || statusOf(reply) == 404) << path << "\n" << reply;
    EXPECT_EQ(reply.find("SECRET"), std::string::npos) << path;
  }
}

// The server keeps serving after all of the above on one connection after another (keep-alive requests too).
TEST(ViewerServerHostile, KeptAliveConnectionsServeInTurn) {
  const auto s = serveHostile();
  RawConnection c(s->port());
  const std::string request = "GET /files/file.bin HTTP/1.1\r\n" + s->host() + "Range: bytes=0-1\r\n\r\n";
  c.send(request + request + request);  // pipelined
  const std::string replies = c.readUntilClosed(milliseconds(1000));
  std::size_t count = 0;
  for (std::size_t at = replies.find("HTTP/1.1 206"); at != std::string::npos; at = replies.find("HTTP/1.1 206", at + 1))
    ++count;
  EXPECT_EQ(count, 3u) << replies;
}

}  // namespace
}  // namespace amos::viewer
