#include "amos/dynamic/baseline_history.h"

#include <utility>

namespace amos::dynamic {

void BaselineHistory::add(BaselineFrame frame) {
  if (frames_ == 0) return;
  frames_back_.push_back(std::move(frame));
  if (frames_back_.size() > frames_) frames_back_.pop_front();
}

const BaselineFrame* BaselineHistory::baseline() const {
  return frames_ > 0 && frames_back_.size() >= frames_ ? &frames_back_.front() : nullptr;
}

}  // namespace amos::dynamic
