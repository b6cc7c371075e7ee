#include "amos/core/thread_signals.h"

#include <pthread.h>
#include <signal.h>

namespace amos::core {

void blockTerminationSignalsInThisThread() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
}

}  // namespace amos::core
