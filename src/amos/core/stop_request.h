#pragma once
// A request to stop (Ctrl-C, SIGTERM, a test), shared by whoever asks and whoever waits: a flag read at frame
// boundaries, plus callbacks that wake the waits that would otherwise outlast it (a paced source waiting for its
// next time stamp, the feeder waiting for a frame). Shutdown is a message: request() runs the callbacks, which
// notify their condition variables; nothing polls the flag in a loop. (std::stop_source / std::stop_callback, in
// C++17.)
//
//   core::StopRequest stop;
//   auto wake = stop.onStop([&] { slot.close(); });  // wakes a take() waiting on the slot
//   ... stop.request();                               // from any thread (not from a signal handler)
//
// Thread-safe. A callback runs once: in the thread that calls request(), or at once in onStop() when the stop was
// already requested. It must not call onStop() or destroy a Subscription of the same StopRequest.
#include <atomic>
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>

namespace amos::core {

class StopRequest {
 public:
  // Unsubscribes (in its destructor) the callback onStop() registered; waits for it when it is running.
  class Subscription {
   public:
    Subscription() = default;
    Subscription(StopRequest* owner, std::size_t id) : owner_(owner), id_(id) {}
    Subscription(Subscription&& other) noexcept : owner_(other.owner_), id_(other.id_) { other.owner_ = nullptr; }
    Subscription& operator=(Subscription&& other) noexcept {
      if (this != &other) {
        reset();
        owner_ = other.owner_;
        id_ = other.id_;
        other.owner_ = nullptr;
      }
      return *this;
    }
    Subscription(const Subscription&) = delete;
    Subscription& operator=(const Subscription&) = delete;
    ~Subscription() { reset(); }
    void reset() {
      if (owner_ != nullptr) owner_->unsubscribe(id_);
      owner_ = nullptr;
    }

   private:
    StopRequest* owner_ = nullptr;
    std::size_t id_ = 0;
  };

  StopRequest() = default;
  StopRequest(const StopRequest&) = delete;
  StopRequest& operator=(const StopRequest&) = delete;

  // Sets the flag and runs the callbacks (the first call only).
  void request() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (requested_.exchange(true)) return;
    for (auto& [id, callback] : callbacks_) callback();
  }
  bool requested() const { return requested_.load(); }

  // Calls `callback` when a stop is requested (at once when it already was) until the Subscription goes.
  [[nodiscard]] Subscription onStop(std::function<void()> callback) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (requested_.load()) {
      callback();
      return {};
    }
    const std::size_t id = next_id_++;
    callbacks_.emplace(id, std::move(callback));
    return {this, id};
  }

 private:
  void unsubscribe(std::size_t id) {
    std::lock_guard<std::mutex> lock(mutex_);
    callbacks_.erase(id);
  }

  std::mutex mutex_;  // held while the callbacks run: a Subscription that goes waits for its callback
  std::atomic<bool> requested_{false};
  std::map<std::size_t, std::function<void()>> callbacks_;
  std::size_t next_id_ = 0;
};

}  // namespace amos::core
