#include "amos/run/paced_feeder.h"

#include <optional>
#include <utility>

namespace amos::run {

PacedFeeder::PacedFeeder(io::FrameSource& source, system::DynamicPipeline& pipeline)
    : source_(source), pipeline_(pipeline), thread_([this] { run(); }) {}

PacedFeeder::~PacedFeeder() {
  stop();
  thread_.join();
}

void PacedFeeder::stop() {
  std::lock_guard<std::mutex> lock(mutex_);
  stopping_ = true;
  changed_.notify_all();
}

void PacedFeeder::run() {
  try {
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        changed_.wait(lock, [&] { return stopping_ || pushed_ == taken_; });  // stage A is free
        if (stopping_) break;
      }
      std::optional<io::RgbdFrame> frame = source_.next();  // the newest frame, or the next one to arrive
      if (!frame) {
        std::lock_guard<std::mutex> lock(mutex_);
        ended_ = true;
        break;
      }
      // Outside the lock: a push may wait for room in a stage-A lane, and stage B must not wait for that.
      pipeline_.push(std::move(*frame));
      std::lock_guard<std::mutex> lock(mutex_);
      ++pushed_;
      changed_.notify_all();
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    error_ = std::current_exception();
    ended_ = true;
  }
  changed_.notify_all();
}

bool PacedFeeder::nextForStageB() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return pushed_ > taken_ || ended_ || stopping_; });
  if (pushed_ > taken_ && !stopping_) {
    ++taken_;
    changed_.notify_all();
    return true;
  }
  if (error_) std::rethrow_exception(error_);
  return false;
}

}  // namespace amos::run
