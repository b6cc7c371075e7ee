#include "amos/match/fuse.h"

#include <fmt/format.h>
#include <unordered_set>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/feature/descriptor_distance.h"

namespace amos::match {

void FusionOptions::check() const {
  core::requireAtLeast(neighbors, "neighbors", 1);
  core::requireAtLeast(second_neighbors, "second_neighbors", 0);
  core::requirePositive(radius, "radius");
  core::requireOption(max_distance > 0 && max_distance <= 256, core::option(max_distance, "max_distance"),
                      fmt::format("must be in (0, 256], got {}", max_distance));
}

int fusePoints(map::Map& map, const map::KeyFramePtr& kf, const std::vector<map::MapPointPtr>& points,
               const FusionOptions& options) {
  const map::Sensor& s = kf->sensor();
  const map::FrameFeatures& f = kf->features();
  const core::SE3 T = kf->T_cw();
  const Eigen::Vector3d O = kf->center();
  int fused = 0;
  std::vector<int> candidates;  // reused: one allocation for the whole search
  for (map::MapPointPtr p : points) {
    if (!p || p->isBad() || p->isObservedBy(kf->id())) continue;
    const Eigen::Vector3d pw = p->position();
    const Eigen::Vector3d pc = T * pw;
    if (pc.z() <= 0) continue;
    const double inv_z = 1.0 / pc.z();
    const double u = s.camera().fx() * pc.x() * inv_z + s.camera().cx();
    const double v = s.camera().fy() * pc.y() * inv_z + s.camera().cy();
    if (!s.inBounds(u, v)) continue;
    const double ur = u - s.bf() * inv_z;
    const Eigen::Vector3d po = pw - O;
    const double dist = po.norm();
    if (dist < p->minDistance() || dist > p->maxDistance()) continue;
    if (p->normal().squaredNorm() > 0 && po.dot(p->normal()) < 0.5 * dist) continue;
    const int level = p->predictScale(dist, s);
    const double radius = options.radius * s.scales()[level];
    f.grid.featuresInArea(u, v, radius, -1, -1, candidates);
    const std::uint8_t* d = p->descriptor().ptr<std::uint8_t>(0);
    int best = 257, best_idx = -1;
    for (const int idx : candidates) {
      const cv::KeyPoint& kp = f.keys[idx];
      if (kp.octave < level - 1 || kp.octave > level) continue;
      const double ex = u - kp.pt.x, ey = v - kp.pt.y;
      const double inv_s2 = s.invSigma2()[kp.octave];
      if (f.u_right[idx] >= 0) {
        const double er = ur - f.u_right[idx];
        if ((ex * ex + ey * ey + er * er) * inv_s2 > 7.8) continue;
      } else if ((ex * ex + ey * ey) * inv_s2 > 5.99) {
        continue;
      }
      const int dd = feature::hammingDistance(d, f.descriptors.ptr<std::uint8_t>(idx));
      if (dd < best) {
        best = dd;
        best_idx = idx;
      }
    }
    if (best_idx < 0 || best > options.max_distance) continue;
    const map::MapPointPtr existing = kf->mapPoint(best_idx);
    if (existing && !existing->isBad()) {
      if (existing->numObservations() > p->numObservations()) {
        map.replaceMapPoint(p, existing);
      } else {
        map.replaceMapPoint(existing, p);
      }
    } else {
      map.addObservation(p, kf, best_idx);
    }
    ++fused;
  }
  return fused;
}

int fuseWithNeighbors(map::Map& map, const map::KeyFramePtr& kf, const FusionOptions& options) {
  std::vector<map::KeyFramePtr> targets;
  std::unordered_set<map::KeyFrameId> in_targets{kf->id()};
  for (const map::KeyFrameId id : kf->bestCovisibles(options.neighbors)) {
    const map::KeyFramePtr n = map.keyFrame(id);
    if (!n || n->isBad() || !in_targets.insert(id).second) continue;
    targets.push_back(n);
  }
  const std::size_t first = targets.size();
  for (std::size_t k = 0; k < first; ++k) {
    for (const map::KeyFrameId id : targets[k]->bestCovisibles(options.second_neighbors)) {
      const map::KeyFramePtr n = map.keyFrame(id);
      if (!n || n->isBad() || !in_targets.insert(id).second) continue;
      targets.push_back(n);
    }
  }
  int fused = 0;
  // The keyframe's points into each neighbour.
  const std::vector<map::MapPointPtr> own = kf->mapPoints();  // a copy: fusion rewrites the keyframe's slots
  for (const auto& t : targets) fused += fusePoints(map, t, own, options);
  // The neighbours' points into the keyframe.
  std::vector<map::MapPointPtr> candidates;
  std::unordered_set<const map::MapPoint*> seen;
  for (const auto& t : targets) {
    for (const auto& p : t->mapPoints()) {
      if (p && !p->isBad() && seen.insert(p.get()).second) candidates.push_back(p);
    }
  }
  fused += fusePoints(map, kf, candidates, options);
  for (const auto& p : kf->mapPoints()) {
    if (p && !p->isBad()) {
      map.updateDescriptor(p);
      map.updateNormalAndDepth(p);
    }
  }
  map.updateConnections(kf);
  return fused;
}

}  // namespace amos::match
