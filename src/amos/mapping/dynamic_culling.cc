#include "amos/mapping/dynamic_culling.h"

#include <fmt/format.h>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::mapping {

void DynamicCullingOptions::check() const {
  core::requireAtLeast(min_hits, "min_hits", 1);
  core::requireOption(min_ratio > 0 && min_ratio <= 1, core::option(min_ratio, "min_ratio"),
                      fmt::format("must be in (0, 1], got {}", min_ratio));
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
