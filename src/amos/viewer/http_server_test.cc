#include "amos/viewer/http_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <opencv2/imgcodecs.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"
#include "amos/viewer/frame_image.h"

namespace amos::viewer {
namespace {

namespace fs = std::filesystem;

struct HttpServed {
  fs::path run;
  LiveState state;
  std::unique_ptr<ViewerServer> server;
  httplib::Client client() const { return httplib::Client("127.0.0.1", server->port()); }
};

std::unique_ptr<HttpServed> serve() {
  auto s = std::make_unique<HttpServed>();
  const fs::path parent = amos::testing::scratchDirForThisTest("viewer_http_");
  s->run = parent / "run";
  fs::create_directories(s->run / "overlays");
  std::ofstream(s->run / "stats.json") << R"({"frames": 1})";
  std::ofstream(parent / "secret.txt") << "SECRET";
  ServerOptions options;
  options.port = 0;
  options.run_folder = s->run;
  s->server = std::make_unique<ViewerServer>(s->state, options);
  return s;
}

TEST(ViewerServer, ServesThePageThreeJsAndTheState) {
  const auto s = serve();
  auto c = s->client();
  const auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("viewer.js"), std::string::npos);
  for (const char* path : {"/viewer.js", "/viewer.css", "/three/three.min.js", "/three/OrbitControls.js"}) {
    const auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 200) << path;
  }
  LiveUpdate u;
  u.map.points.push_back({4, Eigen::Vector3f(1, 2, 3), 0});
  s->state.apply(u);
  const auto state = c.Get("/api/state");
  ASSERT_TRUE(state);
  const nlohmann::json j = nlohmann::json::parse(state->body);
  EXPECT_EQ(j["points"][0][0], 4);
  EXPECT_EQ(s->server->url().rfind("http://127.0.0.1:", 0), 0u);
}

TEST(ViewerServer, ServesDenseLayersAsBinary) {
  const auto s = serve();
  auto c = s->client();
  EXPECT_EQ(c.Get("/api/dense/live.bin")->status, 404);
  ColouredGeometry cloud;
  cloud.xyz = {0, 0, 1, 1, 0, 1};
  cloud.rgb = {255, 0, 0, 0, 255, 0};
  s->state.setDenseLayer("live", cloud);
  const auto r = c.Get("/api/dense/live.bin");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body.size(), 8u + 2 * 15);
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/octet-stream");
  const auto outside = c.Get("/api/dense/../live.bin");
  EXPECT_TRUE(!outside || outside->status != 200);
}

TEST(ViewerServer, FrameImageDecodes) {
  const auto s = serve();
  auto c = s->client();
  EXPECT_EQ(c.Get("/api/frame.jpg")->status, 404);
  cv::Mat bgr(60, 80, CV_8UC3, cv::Scalar(10, 200, 30));
  s->state.setFrameImage(encodeJpeg(renderFrameOverlay(bgr, cv::Mat(), {{10, 10}})));
  const auto r = c.Get("/api/frame.jpg");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  const cv::Mat decoded = cv::imdecode(std::vector<unsigned char>(r->body.begin(), r->body.end()), cv::IMREAD_COLOR);
  EXPECT_EQ(decoded.size(), bgr.size());
}

TEST(ViewerServer, RefusesPathsOutsideTheRun) {
  const auto s = serve();
  auto c = s->client();
  const auto ok = c.Get("/files/stats.json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  for (const char* path : {"/files/../secret.txt", "/files/%2e%2e/secret.txt", "/files/overlays/%2E%2E/../secret.txt",
                           "/files//etc/passwd", "/files/%2Fetc%2Fpasswd", "/files/..%2Fsecret.txt", "/files/"}) {
    const auto r = c.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_NE(r->status, 200) << path;
    EXPECT_EQ(r->body.find("SECRET"), std::string::npos) << path;
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << path;
  }
}

TEST(ViewerServer, IsReadOnly) {
  const auto s = serve();
  auto c = s->client();
  const auto r = c.Post("/api/state", "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_NE(r->status, 200);
}

TEST(ViewerServer, EventStreamDeliversUpdatesAfterTheGivenSeq) {
  const auto s = serve();
  s->state.apply(LiveUpdate{});  // seq 1, before the browser connected
  std::thread writer([&] {
    LiveUpdate u;
    u.map.points.push_back({9, Eigen::Vector3f(1, 2, 3), 0});
    s->state.apply(u);  // seq 2
  });
  auto c = s->client();
  std::string received;
  c.Get("/api/events?since=1", [&](const char* data, std::size_t n) {
    received.append(data, n);
    return received.find("\n\n", received.find("event: update")) == std::string::npos;  // stop after one event
  });
  writer.join();
  EXPECT_NE(received.find("id: 2\nevent: update\ndata: {"), std::string::npos) << received;
  EXPECT_EQ(received.find("id: 1\n"), std::string::npos) << received;
  EXPECT_NE(received.find("[9,1.0,2.0,3.0]"), std::string::npos) << received;
}

// A port in use, by another viewer too, is an error at start naming the port: no SO_REUSEPORT sharing, with which
// the second server listened beside the first and took half of its connections.
TEST(ViewerServer, APortInUseIsAnErrorNamingIt) {
  const auto first = serve();
  LiveState state;
  ServerOptions options;
  options.port = first->server->port();
  try {
    ViewerServer second(state, options);
    FAIL() << "a second server listens on port " << options.port;
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("port " + std::to_string(options.port) + " is in use"), std::string::npos)
        << e.what();
  }
}

// An event stream opened by hand: the request sent, its first bytes read (it is being served), left open.
int openEventStream(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) return -1;
  const std::string request = "GET /api/events HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n\r\n";
  if (send(fd, request.data(), request.size(), 0) != static_cast<ssize_t>(request.size())) return -1;
  char head[16];
  if (recv(fd, head, sizeof(head), 0) <= 0) return -1;
  return fd;
}

// Eight open tabs (event streams, each holding a request thread) do not block the other requests; beyond the
// limit a stream is refused, not queued behind the others.
TEST(ViewerServer, OpenEventStreamsDoNotBlockOtherRequests) {
  const auto s = serve();
  std::vector<int> streams;
  for (int i = 0; i < 8; ++i) {
    streams.push_back(openEventStream(s->server->port()));
    ASSERT_GE(streams.back(), 0) << i;
  }
  auto c = s->client();
  c.set_read_timeout(3, 0);
  const auto start = std::chrono::steady_clock::now();
  const auto r = c.Get("/api/state");
  ASSERT_TRUE(r) << "no answer with 8 event streams open";
  EXPECT_EQ(r->status, 200);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  for (int i = 8; i < ViewerServer::kMaxEventStreams; ++i) streams.push_back(openEventStream(s->server->port()));
  const auto refused = c.Get("/api/events");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 503);
  EXPECT_EQ(c.Get("/api/state")->status, 200);
  for (const int fd : streams) close(fd);
}

}  // namespace
}  // namespace amos::viewer
