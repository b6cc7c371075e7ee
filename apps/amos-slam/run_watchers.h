#pragma once
// What watches `amos-slam run`: the live viewer (--viewer: server, LiveState, snapshot publisher) and the
// report.html recorder, wired to the run as run::RunObservers. Without the viewer module (AMOS_BUILD_VIEWER off)
// --viewer is an error and no report.html is written.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "amos/run/run_observer.h"

namespace amos::app {

struct ViewerArgs {
  bool enabled = false;  // --viewer
  int port = 8090;       // --viewer-port
  std::string bind = "127.0.0.1";  // --viewer-bind
  bool hold = false;     // --viewer-hold: keep serving after the run until Ctrl-C
};

class RunWatchers {
 public:
  // Starts the viewer's server (its address on stderr) when asked for; throws core::Error when it cannot.
  explicit RunWatchers(const ViewerArgs& viewer);
  ~RunWatchers();
  std::vector<run::RunObserver*> observers();
  // Where a dense map's live cloud goes (xyz and rgb, 3 values per point): the viewer's publisher, which thins and
  // throttles it; empty without --viewer.
  using DenseCloudSink = std::function<void(std::vector<float> xyz, std::vector<std::uint8_t> rgb)>;
  DenseCloudSink denseCloudSink();
  // What writeReport writes into the output folder (report.html; nothing without the viewer module).
  static std::vector<std::string> outputNames();
  // Writes <output>/report.html from what was recorded and the run's stats.json (after writeRunOutputs).
  void writeReport(const std::string& output, const std::string& config_file, const std::string& options_json);
  // With --viewer-hold: serves until SIGINT / SIGTERM.
  void holdIfAsked();

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace amos::app
