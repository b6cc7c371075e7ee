#include "amos/tracking/matching.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "amos/core/error.h"
#include "amos/match/descriptor_distance.h"
#include "amos/match/rotation_consistency.h"

namespace amos::tracking {

void MatchingOptions::check() const {
  core::require(th_high > 0 && th_high <= 256, "Matching.thHigh must be in (0, 256], got " + std::to_string(th_high));
  core::require(th_low > 0 && th_low <= th_high, "Matching.thLow must be in (0, thHigh], got " + std::to_string(th_low));
  core::require(local_ratio > 0 && local_ratio <= 1, "Matching.localRatio must be in (0, 1]");
  core::require(brute_force_ratio > 0 && brute_force_ratio <= 1, "Matching.bruteForceRatio must be in (0, 1]");
}

std::vector<bool> rotationConsistent(const std::vector<float>& deltas) {
  match::RotationHistogram histogram;
  for (std::size_t k = 0; k < deltas.size(); ++k) histogram.add(static_cast<int>(k), deltas[k], 0.0f);
  std::vector<bool> keep(deltas.size(), false);
  for (const int k : histogram.consistent()) keep[k] = true;
  return keep;
}

namespace {

// Applies the rotation check to matches recorded as (frame index, rotation delta): rejected ones are cleared.
void filterByRotation(map::Frame& frame, const std::vector<int>& indices, const std::vector<float>& deltas, int& n) {
  const std::vector<bool> keep = rotationConsistent(deltas);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (!keep[k] && frame.map_points[indices[k]]) {
      frame.map_points[indices[k]].reset();
      --n;
    }
  }
}

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

int searchLastFrame(map::Frame& current, const map::Frame& last, double th, const MatchingOptions& options) {
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
    std::vector<int> candidates;
    if (forward) {
      candidates = cf.featuresInArea(u, v, radius, octave, -1);
    } else if (backward) {
      candidates = cf.featuresInArea(u, v, radius, 0, octave);
    } else {
      candidates = cf.featuresInArea(u, v, radius, std::max(0, octave - 1), octave + 1);
    }
    if (candidates.empty()) continue;
    const double ur = u - s.bf() * inv_z;
    const std::uint8_t* d = lf.descriptors.ptr<std::uint8_t>(static_cast<int>(i));
    int best_dist = 256, best_idx = -1;
    for (const int idx : candidates) {
      if (alreadyMatched(current, idx)) continue;
      if (cf.u_right[idx] > 0 && std::abs(ur - cf.u_right[idx]) > radius) continue;
      const int dist = match::hammingDistance(d, cf.descriptors.ptr<std::uint8_t>(idx));
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
  if (options.check_orientation) filterByRotation(current, matched_idx, rot, n);
  return n;
}

int searchLocalPoints(map::Frame& frame, const std::vector<ProjectedPoint>& points, double th,
                      const MatchingOptions& options) {
  const map::Sensor& s = *frame.sensor;
  const map::FrameFeatures& f = *frame.features;
  int n = 0;
  for (const ProjectedPoint& pp : points) {
    const double r = (pp.view_cos > 0.998 ? 2.5 : 4.0) * th;
    const double radius = r * s.scales()[pp.level];
    const std::vector<int> candidates = f.featuresInArea(pp.u, pp.v, radius, pp.level - 1, pp.level);
    if (candidates.empty()) continue;
    const std::uint8_t* d = pp.point->descriptor().ptr<std::uint8_t>(0);
    int best = 256, second = 256, best_level = -1, second_level = -1, best_idx = -1;
    for (const int idx : candidates) {
      if (alreadyMatched(frame, idx)) continue;
      if (f.u_right[idx] > 0 && std::abs(pp.u_right - f.u_right[idx]) > radius) continue;
      const int dist = match::hammingDistance(d, f.descriptors.ptr<std::uint8_t>(idx));
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

int searchKeyFrameByProjection(map::Frame& frame, const map::KeyFrame& kf,
                               const std::unordered_set<const map::MapPoint*>& already, double th, int max_distance,
                               const MatchingOptions& options) {
  const map::Sensor& s = *frame.sensor;
  const map::FrameFeatures& f = *frame.features;
  const Eigen::Vector3d ow = frame.center();
  std::vector<int> matched_idx;
  std::vector<float> rot;
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
    const std::vector<int> candidates = f.featuresInArea(u, v, radius, level - 1, level + 1);
    const std::uint8_t* d = p->descriptor().ptr<std::uint8_t>(0);
    int best = 256, best_idx = -1;
    for (const int idx : candidates) {
      if (frame.map_points[idx]) continue;
      const int dd = match::hammingDistance(d, f.descriptors.ptr<std::uint8_t>(idx));
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
  if (options.check_orientation) filterByRotation(frame, matched_idx, rot, n);
  return n;
}

std::vector<map::MapPointPtr> matchFrameToKeyFrame(const map::Frame& frame, const map::KeyFrame& kf, float ratio,
                                                   const MatchingOptions& options, int* num_matches) {
  std::vector<map::MapPointPtr> out(frame.size());
  std::vector<int> kf_index;
  for (int i = 0; i < kf.size(); ++i) {
    const map::MapPointPtr& p = kf.mapPoint(i);
    if (p && !p->isBad()) kf_index.push_back(i);
  }
  int n = 0;
  if (!kf_index.empty() && frame.size() > 0) {
    cv::Mat train(static_cast<int>(kf_index.size()), 32, CV_8U);
    for (std::size_t k = 0; k < kf_index.size(); ++k) {
      kf.features().descriptors.row(kf_index[k]).copyTo(train.row(static_cast<int>(k)));
    }
    const auto matches = match::matchBruteForce(frame.features->descriptors, train, options.th_low, ratio);
    std::vector<int> q;
    std::vector<float> rot;
    for (const auto& m : matches) {
      const int ki = kf_index[m.train];
      q.push_back(m.query);
      rot.push_back(kf.features().keys[ki].angle - frame.features->keys[m.query].angle);
    }
    const std::vector<bool> keep =
        options.check_orientation ? rotationConsistent(rot) : std::vector<bool>(q.size(), true);
    for (std::size_t k = 0; k < matches.size(); ++k) {
      if (!keep[k]) continue;
      out[q[k]] = kf.mapPoint(kf_index[matches[k].train]);
      ++n;
    }
  }
  if (num_matches) *num_matches = n;
  return out;
}

}  // namespace amos::tracking
