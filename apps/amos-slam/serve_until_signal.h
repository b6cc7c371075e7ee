#pragma once
// Waiting for Ctrl-C / SIGTERM while the viewer serves (`view`, `run --viewer-hold`): the signals are blocked in
// the calling thread and taken with sigwait, so nothing polls. The server's threads block them too
// (viewer/http_server.cc), so they reach this wait. Returns the signal's number.
#include <pthread.h>

#include <csignal>

namespace amos::app {

inline int waitForStopSignal() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  int received = 0;
  sigwait(&signals, &received);
  pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
  return received;
}

}  // namespace amos::app
