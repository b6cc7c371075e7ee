#pragma once
// Culling of map points that keep landing in dynamic regions (paper Sec. III-C: keypoints in dynamic regions
// never create points, and points that slipped in while the front end missed a mover are removed once the
// mover is detected again). Evidence is counted by tracking (tracking/dynamic_evidence.h).
#include "amos/map/map.h"

namespace amos::mapping {

struct DynamicCullingOptions {
  // Mapping.dynamicCullMinHits: frames that must have seen the point visible inside a dynamic region; one frame
  // is never enough (a mask can be wrong for a frame, and a dilated mask grazes static points at its edge).
  int min_hits = 3;
  // Mapping.dynamicCullRatio: ... and at least this share of the masked frames that saw it visible.
  double min_ratio = 0.5;
  void check() const;
};

// Marks the qualifying points bad. [exclusive map lock] Returns how many were culled.
int cullDynamicPoints(map::Map& map, const DynamicCullingOptions& options);

}  // namespace amos::mapping
