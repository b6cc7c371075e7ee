#pragma once
// A serial task queue: one worker thread runs the submitted tasks one after the other, in submission order, and
// each submit() returns a future of the task's result (a task's exception is rethrown by that future's get(), in
// the thread that waits for it). The one way this project runs work in the background: the segmentation network
// and the look-ahead preparation of the next frame are each an executor with the tasks that belong to them.
//
//   SerialExecutor worker;
//   std::future<int> answer = worker.submit([] { return 6 * 7; });  // returns at once (blocks only when full)
//   ...
//   int a = answer.get();                                            // waits for this task only
//
// Thread safety: submit() and close() may be called from any thread. Destruction closes the queue, runs the tasks
// already queued (so no future is left without a value) and joins the thread.
#include <cstddef>
#include <future>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>

#include "amos/core/bounded_queue.h"
#include "amos/core/error.h"

namespace amos::core {

class SerialExecutor {
 public:
  // max_queued: tasks that may wait; submit() blocks while that many do.
  explicit SerialExecutor(std::size_t max_queued = 4) : tasks_(max_queued), thread_([this] { run(); }) {}
  ~SerialExecutor() {
    close();
    thread_.join();
  }
  SerialExecutor(const SerialExecutor&) = delete;
  SerialExecutor& operator=(const SerialExecutor&) = delete;

  // Queues `task` (a callable taking no argument). Throws core::Error after close().
  template <typename F>
  std::future<std::invoke_result_t<F>> submit(F&& task) {
    using R = std::invoke_result_t<F>;
    auto typed = std::make_shared<std::packaged_task<R()>>(std::forward<F>(task));
    std::future<R> result = typed->get_future();
    require(tasks_.push(std::packaged_task<void()>([typed] { (*typed)(); })),
            "SerialExecutor::submit after close()");
    return result;
  }

  // Stops accepting tasks; those already queued still run. Idempotent.
  void close() { tasks_.close(); }

 private:
  void run() {
    while (std::optional<std::packaged_task<void()>> task = tasks_.pop()) (*task)();
  }
  BoundedQueue<std::packaged_task<void()>> tasks_;
  std::thread thread_;  // last: started once the queue exists
};

}  // namespace amos::core
