#pragma once
// Which thread receives the run's signals. SIGINT / SIGTERM end a run through the main thread's handler
// (core/stop_request.h); a background thread (and any thread it starts, which inherits its mask) must not take them.
namespace amos::core {

// Blocks SIGINT and SIGTERM in the calling thread.
void blockTerminationSignalsInThisThread();

}  // namespace amos::core
