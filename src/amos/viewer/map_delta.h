#pragma once
// The map as the viewer sees it, and what changed between two looks at it. The publisher thread takes a
// MapSnapshot at a bounded rate (a brief shared lock of the map: ids and positions are copied, nothing else) and
// sends only the difference to the browsers: new and moved points, removed ones, changed keyframes.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "amos/map/map.h"

namespace amos::viewer {

struct PointSample {
  std::uint64_t id = 0;
  Eigen::Vector3f position = Eigen::Vector3f::Zero();
  int dynamic_hits = 0;  // how often it projected into a dynamic mask (map::MapPoint::dynamicHits) ...
  int masked_views = 0;  // ... of the frames with a mask that saw it (map::MapPoint::maskedViews)
};

struct KeyFrameSample {
  std::uint64_t id = 0;
  Eigen::Vector3f position = Eigen::Vector3f::Zero();             // camera centre (T_wc translation)
  Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();   // T_wc rotation
};

struct MapSnapshot {
  std::vector<PointSample> points;        // by increasing id
  std::vector<KeyFrameSample> keyframes;  // by increasing id
};

// Copies the good points and keyframes under a shared lock of map.mutex().
MapSnapshot takeMapSnapshot(const map::Map& map);

struct MapDelta {
  std::vector<PointSample> points;        // new, or moved by more than DeltaOptions::min_move_m
  std::vector<std::uint64_t> removed;     // points gone from the map (culled, fused, ...)
  // Of the removed points, those that meet the dynamic culling rule (mapping/dynamic_culling.h, its default
  // thresholds in DeltaOptions): removed as dynamic, or most likely so (the viewer does not see why a point went);
  // the viewer keeps them in another colour.
  std::vector<PointSample> culled;
  std::vector<KeyFrameSample> keyframes;  // new or moved keyframes
  std::vector<std::uint64_t> removed_keyframes;
  bool empty() const {
    return points.empty() && removed.empty() && keyframes.empty() && removed_keyframes.empty();
  }
};

struct DeltaOptions {
  float min_move_m = 0.001f;      // a point moved by less (bundle adjustment jitter) is not sent again
  float min_turn_rad = 0.001f;    // likewise for keyframe rotations
  int culled_min_hits = 3;          // as mapping::DynamicCullingOptions::min_hits
  double culled_min_ratio = 0.5;    // as mapping::DynamicCullingOptions::min_ratio
};

// What turns `before` into `after` (both sorted by id).
MapDelta diffMaps(const MapSnapshot& before, const MapSnapshot& after, const DeltaOptions& options = {});

}  // namespace amos::viewer
