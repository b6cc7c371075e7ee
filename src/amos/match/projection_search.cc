#include "amos/match/projection_search.h"

#include "amos/feature/descriptor_distance.h"
#include "amos/match/rotation_consistency.h"

namespace amos::match {

void dropRotationInconsistentMatches(map::Frame& frame, const std::vector<int>& indices,
                                     const std::vector<float>& deltas, int& n) {
  const std::vector<bool> keep = rotationConsistent(deltas);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (!keep[k] && frame.map_points[indices[k]]) {
      frame.map_points[indices[k]].reset();
      --n;
    }
  }
}

int searchKeyFrameByProjection(map::Frame& frame, const map::KeyFrame& kf,
                               const std::unordered_set<const map::MapPoint*>& already, double th, int max_distance,
                               const MatchingOptions& options) {
  const map::Sensor& s = *frame.sensor;
  const map::FrameFeatures& f = *frame.features;
  const Eigen::Vector3d ow = frame.center();
  std::vector<int> matched_idx;
  std::vector<float> rot;
  std::vector<int> candidates;  // reused: one allocation for the whole search
  int n = 0;
  for (int i = 0; i < kf.size(); ++i) {
    const map::MapPointPtr& p = kf.mapPoint(i);
    if (!p || p->isBad() || already.count(p.get())) continue;
    const Eigen::Vector3d pc = frame.T_cw * p->position();
    if (pc.z() <= 0) continue;
    const double u = s.camera().fx() * pc.x() / pc.z() + s.camera().cx();
    const double v = s.camera().fy() * pc.y() / pc.z() + s.camera().cy();
    if (!s.inBounds(u, v)) continue;
    const double dist = (p->position() - ow).norm();
    if (dist < p->minDistance() || dist > p->maxDistance()) continue;
    const int level = p->predictScale(dist, s);
    const double radius = th * s.scales()[level];
    f.grid.featuresInArea(u, v, radius, level - 1, level + 1, candidates);
    const std::uint8_t* d = p->descriptor().ptr<std::uint8_t>(0);
    int best = 256, best_idx = -1;
    for (const int idx : candidates) {
      if (frame.map_points[idx]) continue;
      const int dd = feature::hammingDistance(d, f.descriptors.ptr<std::uint8_t>(idx));
      if (dd < best) {
        best = dd;
        best_idx = idx;
      }
    }
    if (best_idx < 0 || best > max_distance) continue;
    frame.map_points[best_idx] = p;
    ++n;
    matched_idx.push_back(best_idx);
    rot.push_back(kf.features().keys[i].angle - f.keys[best_idx].angle);
  }
  if (options.check_orientation) dropRotationInconsistentMatches(frame, matched_idx, rot, n);
  return n;
}

std::unordered_set<const map::MapPoint*> matchedPoints(const map::Frame& frame) {
  std::unordered_set<const map::MapPoint*> matched;
  for (const auto& p : frame.map_points) {
    if (p) matched.insert(p.get());
  }
  return matched;
}

}  // namespace amos::match
