#include "amos/mapping/dynamic_culling.h"

#include "amos/core/error.h"

namespace amos::mapping {

void DynamicCullingOptions::check() const {
  core::require(min_hits >= 1, "Mapping.dynamicCullMinHits must be >= 1");
  core::require(min_ratio > 0 && min_ratio <= 1, "Mapping.dynamicCullRatio must be in (0, 1]");
}

int cullDynamicPoints(map::Map& map, const DynamicCullingOptions& options) {
  int culled = 0;
  for (const map::MapPointId id : map.dynamicPointCandidates(options.min_hits, options.min_ratio)) {
    if (const map::MapPointPtr p = map.mapPoint(id)) {
      map.setMapPointBad(p);
      ++culled;
    }
  }
  return culled;
}

}  // namespace amos::mapping
