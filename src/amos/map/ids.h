#pragma once
// Identifiers of map entities. Ids are assigned in creation order and never reused, so iterating id-ordered
// containers is deterministic.
#include <cstdint>
#include <limits>

namespace amos::map {

using KeyFrameId = std::uint64_t;
using MapPointId = std::uint64_t;
using FrameId = std::uint64_t;

inline constexpr KeyFrameId kNoKeyFrame = std::numeric_limits<KeyFrameId>::max();
inline constexpr MapPointId kNoMapPoint = std::numeric_limits<MapPointId>::max();

}  // namespace amos::map
