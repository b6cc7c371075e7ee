#include "amos/viewer/http_server.h"

#include <fmt/format.h>
#include <httplib.h>
#include <spdlog/spdlog.h>

#include <chrono>

#include "amos/viewer/file_reply.h"
#include "amos/viewer/run_folder.h"
#include "amos/viewer/web_assets.h"
#include "amos/core/whole_file.h"

namespace amos::viewer {
namespace {

std::string sseMessage(std::uint64_t seq, const std::string& event, const std::string& data) {
  return fmt::format("id: {}\nevent: {}\ndata: {}\n\n", seq, event, data);
}

}  // namespace

ServerLimits ViewerServer::limits() {
  ServerLimits limits;
  limits.workers = kRequestThreads;
  return limits;
}

ViewerServer::ViewerServer(LiveState& state, ServerOptions options)
    : state_(state), options_(std::move(options)), server_(limits()) {
  const std::filesystem::path three = threeJsDir();
  three_js_ = core::readWholeFile(three / "build" / "three.min.js").value_or(std::string());
  orbit_controls_js_ =
      core::readWholeFile(three / "examples" / "js" / "controls" / "OrbitControls.js").value_or(std::string());
  if (three_js_.empty())
    spdlog::warn("viewer: {} is missing (install libjs-three): the page has no 3D view",
                 (three / "build" / "three.min.js").string());
  addRoutes();
  port_ = server_.listen(options_.bind, options_.port);
}

ViewerServer::~ViewerServer() { stop(); }

std::string ViewerServer::url() const {
  if (options_.bind == "0.0.0.0") return fmt::format("http://127.0.0.1:{}/", port_);
  if (options_.bind == "::") return fmt::format("http://[::1]:{}/", port_);
  if (options_.bind.find(':') != std::string::npos) return fmt::format("http://[{}]:{}/", options_.bind, port_);
  return fmt::format("http://{}:{}/", options_.bind, port_);
}

void ViewerServer::stop() {
  state_.close();  // ends the event streams
  server_.stop();
}

void ViewerServer::addRoutes() {
  httplib::Server& s = server_.routes();
  auto asset = [](const std::string& name) {
    return [name](const httplib::Request&, httplib::Response& res) {
      const WebAsset* a = findWebAsset(name);
      if (a == nullptr) {
        res.status = 404;
        return;
      }
      res.set_content(std::string(a->content), std::string(a->mime).c_str());
    };
  };
  s.Get("/", asset("index.html"));
  s.Get("/index.html", asset("index.html"));
  s.Get("/viewer.js", asset("viewer.js"));
  s.Get("/viewer.css", asset("viewer.css"));
  auto script = [](const std::string* text) {
    return [text](const httplib::Request&, httplib::Response& res) {
      if (text->empty()) {
        res.status = 404;
        return;
      }
      res.set_header("Cache-Control", "max-age=3600");
      res.set_content(*text, "text/javascript; charset=utf-8");
    };
  };
  s.Get("/three/three.min.js", script(&three_js_));
  s.Get("/three/OrbitControls.js", script(&orbit_controls_js_));
  s.Get("/api/state", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(state_.stateJson().dump(), "application/json");
  });
  // The same as a script, loaded by the page itself (index.html) so that its load event waits for the state.
  s.Get("/api/state.js", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content("window.amosInitialState = " + state_.stateJson().dump() + ";\n", "text/javascript; charset=utf-8");
  });
  s.Get("/api/frame.jpg", [this](const httplib::Request&, httplib::Response& res) {
    const auto image = state_.frameImage();
    if (!image || image->empty()) {
      res.status = 404;
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(std::string(image->begin(), image->end()), "image/jpeg");
  });
  s.Get(R"(/api/dense/(\w+)\.bin)", [this](const httplib::Request& req, httplib::Response& res) {
    const auto layer = state_.denseLayer(req.matches[1]);
    if (!layer) {
      res.status = 404;
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(*layer, "application/octet-stream");
  });
  s.Get("/api/events", [this](const httplib::Request& req, httplib::Response& res) {
    std::uint64_t since = state_.seq();
    try {
      if (req.has_param("since")) since = std::stoull(req.get_param_value("since"));
      if (req.has_header("Last-Event-ID")) since = std::stoull(req.get_header_value("Last-Event-ID"));
    } catch (const std::exception&) {
      res.status = 400;
      return;
    }
    res.set_header("Cache-Control", "no-store");
    if (event_streams_.fetch_add(1) >= kMaxEventStreams) {
      event_streams_.fetch_sub(1);
      res.status = 503;
      res.set_header("Retry-After", "5");
      res.set_content(fmt::format("too many event streams open (at most {}): close a tab\n", kMaxEventStreams),
                      "text/plain");
      return;
    }
    auto cursor = std::make_shared<std::uint64_t>(since);
    res.set_chunked_content_provider("text/event-stream", [this, cursor](std::size_t, httplib::DataSink& sink) {
      const EventBatch batch = state_.eventsAfter(*cursor, std::chrono::seconds(1));
      if (batch.closed && batch.events.empty()) {
        sink.done();
        return true;
      }
      std::string out;
      if (batch.reload) {
        out = sseMessage(state_.seq(), "reload", "{}");
        *cursor = state_.seq();
      }
      for (const auto& [seq, json] : batch.events) {
        out += sseMessage(seq, "update", json);
        *cursor = seq;
      }
      if (out.empty()) out = ": idle\n\n";  // finds a browser that went away
      return sink.write(out.data(), out.size());
    }, [this](bool) { event_streams_.fetch_sub(1); });
  });
  s.Get(R"(/files/(.*))", [this](const httplib::Request& req, httplib::Response& res) {
    const std::string request = req.matches[1];
    const auto file = options_.run_folder.empty() ? std::nullopt : runFilePath(options_.run_folder, request);
    if (!file) {
      res.status = 403;
      res.set_content("refused: only the files of this run, by a relative path without '..'\n", "text/plain");
      return;
    }
    replyWithFile(*file, req.get_header_value("Range"), res);
  });
}

}  // namespace amos::viewer
