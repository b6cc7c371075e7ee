#include "amos/core/serial_executor.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace amos::core {
namespace {

TEST(SerialExecutor, RunsTasksInSubmissionOrderOnOneOtherThread) {
  std::vector<int> order;  // touched by the worker only, read after every future is ready
  std::thread::id worker_id;
  std::vector<std::future<int>> results;
  {
    SerialExecutor executor(2);  // fewer slots than tasks: submit() waits, nothing is lost
    for (int i = 0; i < 20; ++i) {
      results.push_back(executor.submit([&order, &worker_id, i] {
        if (i == 0) worker_id = std::this_thread::get_id();
        EXPECT_EQ(worker_id, std::this_thread::get_id());
        order.push_back(i);
        return i * i;
      }));
    }
    for (int i = 0; i < 20; ++i) EXPECT_EQ(results[i].get(), i * i);
  }
  EXPECT_NE(worker_id, std::this_thread::get_id());
  ASSERT_EQ(order.size(), 20u);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(order[i], i);
}

TEST(SerialExecutor, ATaskExceptionReachesItsFutureAndTheNextTasksStillRun) {
  SerialExecutor executor;
  std::future<void> failing = executor.submit([] { throw std::runtime_error("bad frame"); });
  std::future<std::string> next = executor.submit([] { return std::string("still running"); });
  EXPECT_THROW(failing.get(), std::runtime_error);
  EXPECT_EQ(next.get(), "still running");
}

TEST(SerialExecutor, QueuedTasksRunBeforeDestructionAndSubmitAfterCloseThrows) {
  std::future<int> late;
  {
    SerialExecutor executor;
    executor.submit([] { std::this_thread::sleep_for(std::chrono::milliseconds(20)); });  // keeps the worker busy
    late = executor.submit([] { return 7; });
    executor.close();
    EXPECT_THROW(executor.submit([] { return 0; }), Error);
  }
  EXPECT_EQ(late.get(), 7);
}

}  // namespace
}  // namespace amos::core
