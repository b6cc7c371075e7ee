#include "amos/api/allocator_tuning.h"

#include <mutex>  // before the test: __GLIBC__ comes with the C library's headers

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace amos::api {

void tuneAllocatorOnce() {
#if defined(__GLIBC__)
  static std::once_flag once;  // the allocator is the process's: set once, whichever Slam comes first
  std::call_once(once, [] {
    mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
  });
#endif
}

}  // namespace amos::api
