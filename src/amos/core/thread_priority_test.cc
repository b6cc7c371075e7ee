// lowerThisThreadPriority changes the calling thread's nice value only.
#include "amos/core/thread_priority.h"

#include <gtest/gtest.h>

#include <thread>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace amos::core {
namespace {

int threadNice() { return getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid))); }

TEST(ThreadPriority, LowersTheCallingThreadOnly) {
  const int main_before = threadNice();
  int before = 0, after = 0;
  bool ok = false;
  std::thread worker([&] {
    before = threadNice();
    ok = lowerThisThreadPriority(3);
    after = threadNice();
  });
  worker.join();
  ASSERT_TRUE(ok);
  EXPECT_EQ(after, std::min(19, before + 3));
  EXPECT_EQ(threadNice(), main_before) << "the calling thread's change leaked to another thread";
}

}  // namespace
}  // namespace amos::core
#endif
