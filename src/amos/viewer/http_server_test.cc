#include "amos/viewer/http_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <thread>

#include "amos/testing/scratch_dir.h"
#include "amos/viewer/frame_image.h"

namespace amos::viewer {
namespace {

namespace fs = std::filesystem;

struct Served {
  fs::path run;
  LiveState state;
  std::unique_ptr<ViewerServer> server;
  httplib::Client client() const { return httplib::Client("127.0.0.1", server->port()); }
};

std::unique_ptr<Served> serve() {
  auto s = std::make_unique<Served>();
  const fs::path parent = testing::scratchDirForThisTest("viewer_http_");
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

}  // namespace
}  // namespace amos::viewer
