#pragma once
// A one-frame "newest wins" hand-over between a producer that runs at its own rate (a replay clock, a camera
// driver) and the SLAM loop: a frame put while an older one still waits replaces it, and the older one is counted
// as dropped. The consumer blocks on a condition variable; close() ends the stream (a message, not a polled flag).
// Thread-safe: any number of producers, one consumer.
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>

#include "amos/io/frame_source.h"
#include "amos/io/rgbd_frame.h"

namespace amos::io {

class NewestFrameSlot {
 public:
  // Stamps frame.arrival with the current steady-clock time and makes it the waiting frame. Returns false (and
  // does nothing) once the slot is closed.
  bool put(RgbdFrame frame);
  // Blocks until a frame waits or the slot is closed. After close() the waiting frame is still handed out; then
  // the error given to close() is rethrown, or nullopt returned.
  std::optional<RgbdFrame> take();
  // The waiting frame, if any; never blocks and never throws.
  std::optional<RgbdFrame> tryTake();
  // Ends the stream; `error` (may be null) is rethrown by take() once the slot is empty. Idempotent: the first
  // call decides the error.
  void close(std::exception_ptr error = nullptr);
  bool closed() const;
  SourceStats stats() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::optional<RgbdFrame> frame_;
  bool closed_ = false;
  std::exception_ptr error_;
  SourceStats stats_;
};

}  // namespace amos::io
