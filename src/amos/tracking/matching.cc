#include "amos/tracking/matching.h"

#include <algorithm>
#include <cmath>

#include "amos/feature/descriptor_distance.h"
#include "amos/match/projection_search.h"

namespace amos::tracking {

namespace {

bool alreadyMatched(const map::Frame& frame, int idx) {
  const auto& p = frame.map_points[idx];
  return p && p->numObservations() > 0;
}

}  // namespace

bool projectIntoFrame(const map::Frame& frame, const map::MapPointPtr& p, double min_view_cos, ProjectedPoint& out) {
  const Eigen::Vector3d& pw = p->position();
  const Eigen::Vector3d pc = frame.T_cw * pw;
  if (pc.z() <= 0) return false;
  const map::Sensor& s = *frame.sensor;
  const double inv_z = 1.0 / pc.z();
  const double u = s.camera().fx() * pc.x() * inv_z + s.camera().cx();
  const double v = s.camera().fy() * pc.y() * inv_z + s.camera().cy();
  if (!s.inBounds(u, v)) return false;
  const Eigen::Vector3d po = pw - frame.center();
  const double dist = po.norm();
  if (dist < p->minDistance() || dist > p->maxDistance()) return false;
  const Eigen::Vector3d& n = p->normal();
  const double view_cos = n.squaredNorm() > 0 ? po.dot(n) / dist : 1.0;
  if (view_cos < min_view_cos) return false;
  out.point = p;
  out.u = u;
  out.v = v;
  out.u_right = u - s.bf() * inv_z;
  out.z = pc.z();
  out.level = p->predictScale(dist, s);
  out.view_cos = view_cos;
  return true;
}

int searchLastFrame(map::Frame& current, const map::Frame& last, double th,
                    const match::MatchingOptions& options) {
  const map::Sensor& s = *current.sensor;
  const map::FrameFeatures& cf = *current.features;
  const map::FrameFeatures& lf = *last.features;
  // Where the current camera centre lies in the last camera: forward motion means points grow (finer levels
  // in the last frame appear at coarser ones now), backward the opposite.
  const Eigen::Vector3d t_lc = last.T_cw * current.center();
  const bool forward = t_lc.z() > s.baseline();
  const bool backward = -t_lc.z() > s.baseline();
  std::vector<int> matched_idx;
  std::vector<float> rot;
  std::vector<int> candidates;  // reused: one allocation for the whole search
  int n = 0;
  for (std::size_t i = 0; i < last.size(); ++i) {
    const map::MapPointPtr& p = last.map_points[i];
    if (!p || last.outlier[i]) continue;
    const Eigen::Vector3d pc = current.T_cw * p->position();
    if (pc.z() <= 0) continue;
    const double inv_z = 1.0 / pc.z();
    const double u = s.camera().fx() * pc.x() * inv_z + s.camera().cx();
    const double v = s.camera().fy() * pc.y() * inv_z + s.camera().cy();
    if (!s.inBounds(u, v)) continue;
    const int octave = lf.keys[i].octave;
    const double radius = th * s.scales()[octave];
    if (forward) {
      cf.grid.featuresInArea(u, v, radius, octave, -1, candidates);
    } else if (backward) {
      cf.grid.featuresInArea(u, v, radius, 0, octave, candidates);
    } else {
      cf.grid.featuresInArea(u, v, radius, std::max(0, octave - 1), octave + 1, candidates);
    }
    if (candidates.empty()) continue;
    const double ur = u - s.bf() * inv_z;
    const std::uint8_t* d = lf.descriptors.ptr<std::uint8_t>(static_cast<int>(i));
    int best_dist = 256, best_idx = -1;
    for (const int idx : candidates) {
      if (alreadyMatched(current, idx)) continue;
      if (cf.u_right[idx] > 0 && std::abs(ur - cf.u_right[idx]) > radius) continue;
      const int dist = feature::hammingDistance(d, cf.descriptors.ptr<std::uint8_t>(idx));
      if (dist < best_dist) {
        best_dist = dist;
        best_idx = idx;
      }
    }
    if (best_idx < 0 || best_dist > options.th_high) continue;
    current.map_points[best_idx] = p;
    ++n;
    matched_idx.push_back(best_idx);
    rot.push_back(lf.keys[i].angle - cf.keys[best_idx].angle);
  }
  if (options.check_orientation) match::dropRotationInconsistentMatches(current, matched_idx, rot, n);
  return n;
}

int searchLocalPoints(map::Frame& frame, const std::vector<ProjectedPoint>& points, double th,
                      const match::MatchingOptions& options) {
  const map::Sensor& s = *frame.sensor;
  const map::FrameFeatures& f = *frame.features;
  std::vector<int> candidates;  // reused: one allocation for the whole search
  int n = 0;
  for (const ProjectedPoint& pp : points) {
    const double r = (pp.view_cos > 0.998 ? 2.5 : 4.0) * th;
    const double radius = r * s.scales()[pp.level];
    f.grid.featuresInArea(pp.u, pp.v, radius, pp.level - 1, pp.level, candidates);
    if (candidates.empty()) continue;
    const std::uint8_t* d = pp.point->descriptor().ptr<std::uint8_t>(0);
    int best = 256, second = 256, best_level = -1, second_level = -1, best_idx = -1;
    for (const int idx : candidates) {
      if (alreadyMatched(frame, idx)) continue;
      if (f.u_right[idx] > 0 && std::abs(pp.u_right - f.u_right[idx]) > radius) continue;
      const int dist = feature::hammingDistance(d, f.descriptors.ptr<std::uint8_t>(idx));
      if (dist < best) {
        second = best;
        second_level = best_level;
        best = dist;
        best_level = f.keys[idx].octave;
        best_idx = idx;
      } else if (dist < second) {
        second = dist;
        second_level = f.keys[idx].octave;
      }
    }
    if (best_idx < 0 || best > options.th_high) continue;
    if (best_level == second_level && best > options.local_ratio * second) continue;
    frame.map_points[best_idx] = pp.point;
    ++n;
  }
  return n;
}

}  // namespace amos::tracking
