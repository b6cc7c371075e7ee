#include "run_watchers.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <optional>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "serve_until_signal.h"
#ifdef AMOS_HAVE_VIEWER
#include "amos/viewer/http_server.h"
#include "amos/viewer/live_state.h"
#include "amos/viewer/report_html.h"
#include "amos/viewer/report_recorder.h"
#include "amos/viewer/snapshot_publisher.h"
#include "amos/core/whole_file.h"
#endif

namespace amos::app {

#ifdef AMOS_HAVE_VIEWER
struct RunWatchers::Parts {
  ViewerArgs args;
  viewer::ReportRecorder recorder;
  std::optional<viewer::LiveState> state;
  std::optional<viewer::ViewerServer> server;
  std::optional<viewer::SnapshotPublisher> publisher;
};

RunWatchers::RunWatchers(const ViewerArgs& viewer) : parts_(std::make_unique<Parts>()) {
  parts_->args = viewer;
  if (!viewer.enabled) return;
  parts_->state.emplace();
  viewer::ServerOptions options;
  options.bind = viewer.bind;
  options.port = viewer.port;
  parts_->server.emplace(*parts_->state, options);
  parts_->publisher.emplace(*parts_->state);
  spdlog::info("viewer: {}", parts_->server->url());
}

RunWatchers::~RunWatchers() = default;

std::vector<run::RunObserver*> RunWatchers::observers() {
  std::vector<run::RunObserver*> out{&parts_->recorder};
  if (parts_->publisher) out.push_back(&*parts_->publisher);
  return out;
}

std::vector<std::string> RunWatchers::outputNames() { return {"report.html"}; }

RunWatchers::DenseCloudSink RunWatchers::denseCloudSink() {
  if (!parts_->publisher) return {};
  viewer::SnapshotPublisher* publisher = &*parts_->publisher;
  return [publisher](std::vector<float> xyz, std::vector<std::uint8_t> rgb) {
    publisher->publishDenseCloud(std::move(xyz), std::move(rgb));
  };
}

void RunWatchers::writeReport(const std::string& output, const std::string& config_file,
                              const std::string& options_json) {
  core::Stopwatch watch;
  viewer::ReportInputs inputs;
  const std::string stats = core::readWholeFile(output + "/stats.json").value_or(std::string());
  inputs.stats = nlohmann::json::parse(stats, nullptr, false);
  inputs.settings_file = config_file;
  inputs.settings_text = core::readWholeFile(config_file).value_or(std::string());
  inputs.run_options = nlohmann::json::parse(options_json, nullptr, false);
  viewer::writeReportHtml(output, parts_->recorder, inputs);
  spdlog::info("report.html written in {:.0f} ms", watch.elapsedMs());
}

void RunWatchers::holdIfAsked() {
  if (!parts_->args.hold || !parts_->server) return;
  waitForStopSignal(fmt::format("viewer: the run has ended; still serving {} until Ctrl-C", parts_->server->url()));
}
#else
struct RunWatchers::Parts {};

RunWatchers::RunWatchers(const ViewerArgs& viewer) {
  core::require(!viewer.enabled, "--viewer: this build has no viewer (install libcpp-httplib-dev and libjs-three, "
                                 "configure with -DAMOS_BUILD_VIEWER=ON)");
}
RunWatchers::~RunWatchers() = default;
std::vector<run::RunObserver*> RunWatchers::observers() { return {}; }
std::vector<std::string> RunWatchers::outputNames() { return {}; }
RunWatchers::DenseCloudSink RunWatchers::denseCloudSink() { return {}; }
void RunWatchers::writeReport(const std::string&, const std::string&, const std::string&) {}
void RunWatchers::holdIfAsked() {}
#endif

}  // namespace amos::app
