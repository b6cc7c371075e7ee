#include "latest_frame.h"

namespace amos::node {

bool LatestFrame::put(StampedFrame frame) {
  {
    std::lock_guard lock(mutex_);
    if (closed_) return false;
    ++received_;
    if (waiting_) ++dropped_;
    waiting_ = std::move(frame);
  }
  ready_.notify_one();
  return true;
}

std::optional<StampedFrame> LatestFrame::take() {
  std::unique_lock lock(mutex_);
  ready_.wait(lock, [this] { return closed_ || waiting_.has_value(); });
  std::optional<StampedFrame> frame = std::move(waiting_);
  waiting_.reset();
  return frame;
}

void LatestFrame::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

std::size_t LatestFrame::received() const {
  std::lock_guard lock(mutex_);
  return received_;
}

std::size_t LatestFrame::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace amos::node
