#include "amos/tracking/id_marks.h"

#include <algorithm>

#include "amos/core/error.h"

namespace amos::tracking {

void IdMarks::clear() {
  if (++stamp_ == 0) {  // wrapped: old stamps could match again
    std::fill(stamps_.begin(), stamps_.end(), 0u);
    stamp_ = 1;
  }
}

bool IdMarks::insert(std::uint64_t id) {
  // Ids are dense from 0; one out of all proportion (e.g. the "no point" sentinel) would allocate without bound.
  if (id >= (std::uint64_t{1} << 32)) throw core::Error("IdMarks::insert: id out of range for a dense id set");
  if (id >= stamps_.size()) stamps_.resize(std::max<std::size_t>(id + 1, stamps_.size() * 3 / 2), 0u);
  if (stamps_[id] == stamp_) return false;
  stamps_[id] = stamp_;
  return true;
}

}  // namespace amos::tracking
