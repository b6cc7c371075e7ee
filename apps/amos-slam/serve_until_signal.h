#pragma once
// Waiting for Ctrl-C / SIGTERM while the viewer serves (`view`, `run --viewer-hold`) without polling: the handler
// posts a semaphore (sem_post is async-signal-safe, whichever thread the signal lands in) and the caller waits on
// it. The previous handlers are put back afterwards. `ready` is logged once the handler is in place, so a signal
// sent by whoever read it is never missed.
#include <semaphore.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <csignal>
#include <string>

namespace amos::app {

namespace hold_detail {
inline sem_t semaphore;
extern "C" inline void onSignal(int) { sem_post(&semaphore); }
}  // namespace hold_detail

inline void waitForStopSignal(const std::string& ready) {
  sem_init(&hold_detail::semaphore, 0, 0);
  struct sigaction action {}, old_int{}, old_term{};
  action.sa_handler = hold_detail::onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);
  spdlog::info("{}", ready);
  while (sem_wait(&hold_detail::semaphore) != 0 && errno == EINTR) {
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  sem_destroy(&hold_detail::semaphore);
}

}  // namespace amos::app
