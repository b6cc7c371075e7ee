// amos-slam view OUTPUT_DIR: the viewer's page for a finished run (its trajectory, keyframes, map, stats, the ground
// truth and mask overlays its report.html keeps, the mask overlays saved with --save-masks, and the dense mesh,
// cloud and removed points of `run --dense`), served on loopback until Ctrl-C. Only the files of that folder are
// served (viewer/run_folder.h). All work is in amos::viewer.
#include <fmt/format.h>

#include <memory>
#include <string>

#include "amos/core/error.h"
#include "commands.h"
#include "serve_until_signal.h"
#ifdef AMOS_HAVE_VIEWER
#include "amos/viewer/http_server.h"
#include "amos/viewer/live_state.h"
#include "amos/viewer/run_folder.h"
#endif

namespace amos::app {
namespace {

struct ViewArgs {
  std::string folder, bind = "127.0.0.1";
  int port = 8090;
};

void viewRun(const ViewArgs& args) {
#ifdef AMOS_HAVE_VIEWER
  viewer::LiveState state;
  viewer::loadRunFolder(args.folder, state);
  viewer::ServerOptions options;
  options.bind = args.bind;
  options.port = args.port;
  options.run_folder = args.folder;
  viewer::ViewerServer server(state, options);
  waitForStopSignal(fmt::format("viewer: {} (the run in {}; Ctrl-C ends)", server.url(), args.folder));
#else
  (void)args;
  throw core::Error("view: this build has no viewer (install libcpp-httplib-dev and libjs-three, configure with "
                    "-DAMOS_BUILD_VIEWER=ON)");
#endif
}

}  // namespace

void addViewCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ViewArgs>();
  auto* cmd = app.add_subcommand("view", "Serve the viewer's page for a finished run's output folder (until Ctrl-C)");
  cmd->add_option("folder", args->folder, "Output folder of `amos-slam run`")->required()->check(CLI::ExistingDirectory);
  // Named as run's viewer flags; --port and --bind are their former names.
  cmd->add_option("--viewer-port,--port", args->port, "Port (default 8090; 0 = any free port)")->check(portNumber());
  cmd->add_option("--viewer-bind,--bind", args->bind, "Address to listen on (default 127.0.0.1, this machine only)");
  cmd->callback([args, &exit_code] {
    viewRun(*args);
    exit_code = 0;
  });
}

}  // namespace amos::app
