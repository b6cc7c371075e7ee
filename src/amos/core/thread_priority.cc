#include "amos/core/thread_priority.h"

#include <cerrno>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace amos::core {

bool lowerThisThreadPriority(int increment) {
#if defined(__linux__)
  // On Linux setpriority(PRIO_PROCESS, tid) acts on the one thread (nice is per thread there).
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int current = getpriority(PRIO_PROCESS, tid);
  if (current == -1 && errno != 0) return false;
  return setpriority(PRIO_PROCESS, tid, current + increment) == 0;
#else
  (void)increment;
  return false;
#endif
}

}  // namespace amos::core
