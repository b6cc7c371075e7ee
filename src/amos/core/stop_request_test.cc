#include "amos/core/stop_request.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace amos::core {
namespace {

TEST(StopRequest, RunsEachCallbackOnceAndAtOnceWhenAlreadyRequested) {
  StopRequest stop;
  int calls = 0, late = 0;
  const StopRequest::Subscription s = stop.onStop([&] { ++calls; });
  EXPECT_FALSE(stop.requested());
  stop.request();
  stop.request();
  EXPECT_TRUE(stop.requested());
  EXPECT_EQ(calls, 1);
  const StopRequest::Subscription t = stop.onStop([&] { ++late; });
  EXPECT_EQ(late, 1);
}

TEST(StopRequest, AGoneSubscriptionIsNotCalled) {
  StopRequest stop;
  int calls = 0;
  { const StopRequest::Subscription s = stop.onStop([&] { ++calls; }); }
  stop.request();
  EXPECT_EQ(calls, 0);
}

// What the run's waits do with it: a condition-variable wait far longer than the test ends as soon as another
// thread requests the stop.
TEST(StopRequest, WakesAWaitFromAnotherThread) {
  StopRequest stop;
  std::mutex mutex;
  std::condition_variable cv;
  bool woken = false;
  const StopRequest::Subscription s = stop.onStop([&] {
    std::lock_guard<std::mutex> lock(mutex);
    woken = true;
    cv.notify_all();
  });
  const auto start = std::chrono::steady_clock::now();
  std::thread requester([&] { stop.request(); });
  {
    std::unique_lock<std::mutex> lock(mutex);
    cv.wait_for(lock, std::chrono::minutes(10), [&] { return woken; });
  }
  requester.join();
  EXPECT_TRUE(woken);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

}  // namespace
}  // namespace amos::core
