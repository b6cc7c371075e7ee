#include "amos/viewer/map_delta.h"

#include <algorithm>
#include <mutex>
#include <shared_mutex>

namespace amos::viewer {

MapSnapshot takeMapSnapshot(const map::Map& map) {
  MapSnapshot s;
  std::shared_lock lock(map.mutex());
  const std::vector<map::MapPointPtr> points = map.mapPoints();
  s.points.reserve(points.size());
  for (const map::MapPointPtr& p : points) {
    if (p->isBad()) continue;
    s.points.push_back({p->id(), p->position().cast<float>(), p->dynamicHits(), p->maskedViews()});
  }
  for (const map::KeyFramePtr& kf : map.keyFrames()) {
    if (kf->isBad()) continue;
    const core::SE3 T_wc = kf->T_wc();
    s.keyframes.push_back({kf->id(), T_wc.translation().cast<float>(),
                           Eigen::Quaternionf(T_wc.rotation().cast<float>())});
  }
  return s;
}

namespace {

// Merge of two id-sorted lists: `changed` for ids in both, `added` for ids only in after, `gone` for ids only in
// before.
template <typename T, typename Changed, typename Added, typename Gone>
void mergeById(const std::vector<T>& before, const std::vector<T>& after, Changed changed, Added added, Gone gone) {
  std::size_t i = 0, j = 0;
  while (i < before.size() || j < after.size()) {
    if (j == after.size() || (i < before.size() && before[i].id < after[j].id)) {
      gone(before[i++]);
    } else if (i == before.size() || after[j].id < before[i].id) {
      added(after[j++]);
    } else {
      changed(before[i++], after[j++]);
    }
  }
}

}  // namespace

MapDelta diffMaps(const MapSnapshot& before, const MapSnapshot& after, const DeltaOptions& options) {
  MapDelta d;
  const float move2 = options.min_move_m * options.min_move_m;
  mergeById(
      before.points, after.points,
      [&](const PointSample& a, const PointSample& b) {
        if ((a.position - b.position).squaredNorm() > move2) d.points.push_back(b);
      },
      [&](const PointSample& b) { d.points.push_back(b); },
      [&](const PointSample& a) {
        d.removed.push_back(a.id);
        if (a.dynamic_hits >= options.culled_min_hits &&
            a.dynamic_hits >= options.culled_min_ratio * std::max(1, a.masked_views))
          d.culled.push_back(a);
      });
  mergeById(
      before.keyframes, after.keyframes,
      [&](const KeyFrameSample& a, const KeyFrameSample& b) {
        if ((a.position - b.position).squaredNorm() > move2 || a.rotation.angularDistance(b.rotation) > options.min_turn_rad)
          d.keyframes.push_back(b);
      },
      [&](const KeyFrameSample& b) { d.keyframes.push_back(b); },
      [&](const KeyFrameSample& a) { d.removed_keyframes.push_back(a.id); });
  return d;
}

}  // namespace amos::viewer
