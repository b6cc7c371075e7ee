#pragma once
// A set of map ids (map points, keyframes: assigned in creation order from 0, so dense) as one stamp per id, for
// the per-frame "seen already?" tests of the local map: a lookup is an array read, and clearing is a new stamp
// instead of freeing and reallocating hash nodes every frame.
#include <cstdint>
#include <vector>

namespace amos::tracking {

class IdMarks {
 public:
  // Empties the set (O(1) but every 2^32nd call, which rewrites the stamps).
  void clear();
  // Adds id; returns whether it was not in the set yet.
  bool insert(std::uint64_t id);
  bool contains(std::uint64_t id) const { return id < stamps_.size() && stamps_[id] == stamp_; }

 private:
  std::vector<std::uint32_t> stamps_;
  std::uint32_t stamp_ = 1;
};

}  // namespace amos::tracking
