#pragma once
// Temporal consistency of loop candidates (ORB-SLAM2's DetectLoop, "covisibility consistency"): a candidate is
// believed only when candidates of several consecutive keyframes point at the same place. A group is a candidate
// with its covisible keyframes; a candidate group that shares a keyframe with a group of the previous keyframe
// inherits that group's consistency + 1, otherwise it starts at 0. A candidate whose consistency reaches
// `required` goes on to geometric verification. A false loop (a similar-looking wall, a repeated shelf) rarely
// stays the best match while the camera moves on for `required` keyframes; a true loop does.
#include <unordered_set>
#include <vector>

#include "amos/map/map.h"

namespace amos::loop {

class LoopConsistency {
 public:
  // `required` = 0 accepts every candidate (no test). ORB-SLAM2 requires 3.
  explicit LoopConsistency(int required) : required_(required) {}

  // The candidates of one keyframe, best first, in; those consistent enough out (same order). Advances the state
  // by one keyframe. Map lock held by the caller (shared is enough).
  std::vector<map::KeyFramePtr> filter(const map::Map& map, const std::vector<map::KeyFramePtr>& candidates);
  // Forget all groups (after a loop was closed: the next loop must be consistent on its own).
  void reset() { groups_.clear(); }

  int required() const { return required_; }

 private:
  struct Group {
    std::unordered_set<map::KeyFrameId> keyframes;
    int consistency = 0;
  };
  int required_;
  std::vector<Group> groups_;
};

}  // namespace amos::loop
