#include "amos/io/newest_frame_slot.h"

#include <chrono>
#include <utility>

namespace amos::io {

bool NewestFrameSlot::put(RgbdFrame frame) {
  frame.arrival = std::chrono::steady_clock::now();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return false;
    if (frame_) ++stats_.dropped;
    ++stats_.delivered;
    frame_ = std::move(frame);
  }
  ready_.notify_one();
  return true;
}

std::optional<RgbdFrame> NewestFrameSlot::take() {
  std::unique_lock<std::mutex> lock(mutex_);
  ready_.wait(lock, [&] { return frame_.has_value() || closed_; });
  if (frame_) {
    std::optional<RgbdFrame> out = std::move(frame_);
    frame_.reset();
    return out;
  }
  if (error_) std::rethrow_exception(error_);
  return std::nullopt;
}

std::optional<RgbdFrame> NewestFrameSlot::tryTake() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<RgbdFrame> out = std::move(frame_);
  frame_.reset();
  return out;
}

void NewestFrameSlot::close(std::exception_ptr error) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return;
    closed_ = true;
    error_ = std::move(error);
  }
  ready_.notify_all();
}

bool NewestFrameSlot::closed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return closed_;
}

SourceStats NewestFrameSlot::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace amos::io
