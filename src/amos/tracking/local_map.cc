#include "amos/tracking/local_map.h"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "amos/tracking/dynamic_evidence.h"

namespace amos::tracking {

map::KeyFramePtr LocalMap::update(map::Frame& frame, const map::Map& map, int max_keyframes) {
  map::KeyFramePtr best = addObservingKeyFrames(frame, map);
  addNeighbours(map, max_keyframes);
  collectPoints();
  return best;
}

void LocalMap::reset(const map::KeyFramePtr& kf) { keyframes_ = {kf}; }

map::KeyFramePtr LocalMap::addObservingKeyFrames(map::Frame& frame, const map::Map& map) {
  // Observations per keyframe id, in a dense array; the keyframes then in ascending id order (as a std::map of the
  // counts would give them).
  observed_ids_.clear();
  for (auto& p : frame.map_points) {
    if (!p) continue;
    if (p->isBad()) {
      p.reset();
      continue;
    }
    for (const auto& [kf_id, index] : p->observations()) {
      if (kf_id >= observation_counts_.size()) observation_counts_.resize(kf_id + 1, 0);
      if (observation_counts_[kf_id]++ == 0) observed_ids_.push_back(kf_id);
    }
  }
  std::sort(observed_ids_.begin(), observed_ids_.end());
  keyframes_.clear();
  map::KeyFramePtr best;
  int best_count = 0;
  for (const map::KeyFrameId kf_id : observed_ids_) {
    const int c = observation_counts_[kf_id];
    observation_counts_[kf_id] = 0;  // ready for the next frame
    map::KeyFramePtr kf = map.keyFrame(kf_id);
    if (!kf || kf->isBad()) continue;
    keyframes_.push_back(kf);
    if (c > best_count) {
      best_count = c;
      best = kf;
    }
  }
  return best;
}

void LocalMap::addNeighbours(const map::Map& map, int max_keyframes) {
  IdMarks& included = keyframe_marks_;
  included.clear();
  for (const auto& kf : keyframes_) included.insert(kf->id());
  const std::size_t direct = keyframes_.size();
  auto add = [&](map::KeyFrameId id) {
    if (included.contains(id)) return false;
    map::KeyFramePtr kf = map.keyFrame(id);
    if (!kf || kf->isBad()) return false;
    keyframes_.push_back(kf);
    included.insert(id);
    return true;
  };
  for (std::size_t k = 0; k < direct; ++k) {
    if (keyframes_.size() > static_cast<std::size_t>(max_keyframes)) break;
    const map::KeyFramePtr kf = keyframes_[k];
    for (const map::KeyFrameId n : kf->bestCovisibles(10)) {
      if (add(n)) break;
    }
    for (const map::KeyFrameId c : kf->children()) {
      if (add(c)) break;
    }
    if (kf->parent() != map::kNoKeyFrame) add(kf->parent());
  }
}

void LocalMap::collectPoints() {
  points_.clear();
  IdMarks& seen = point_marks_;
  seen.clear();
  for (const auto& kf : keyframes_) {
    for (const auto& p : kf->mapPoints()) {
      if (p && !p->isBad() && seen.insert(p->id())) points_.push_back(p);
    }
  }
}

int LocalMap::searchUnmatched(map::Frame& frame, double th, const match::MatchingOptions& matching) const {
  // The frame's matched map points by id (its temporary points, which have none, are not local points anyway).
  IdMarks& in_frame = frame_point_marks_;
  in_frame.clear();
  for (auto& p : frame.map_points) {
    if (!p) continue;
    if (p->isBad()) {
      p.reset();
      continue;
    }
    p->increaseVisible();
    if (p->id() != map::kNoMapPoint) in_frame.insert(p->id());
  }
  const bool masked = !frame.dynamic_mask.empty();
  std::vector<ProjectedPoint> candidates;
  candidates.reserve(points_.size());
  for (const auto& p : points_) {
    if (in_frame.contains(p->id())) continue;
    ProjectedPoint pp;
    if (!projectIntoFrame(frame, p, 0.5, pp)) continue;
    p->increaseVisible();
    if (masked) {
      // Evidence for culling points on movers (Sec. III-C). The mask and depth are in raw image coordinates;
      // the undistorted projection is within a few pixels of it, which is enough for a count.
      const MaskEvidence evidence = maskEvidence(frame.dynamic_mask, frame.depth_image, pp.u, pp.v, pp.z);
      if (evidence != MaskEvidence::kNone) p->increaseMaskedViews();
      if (evidence == MaskEvidence::kDynamic) p->increaseDynamicHits();
    }
    candidates.push_back(std::move(pp));
  }
  if (candidates.empty()) return 0;
  const int found = searchLocalPoints(frame, candidates, th, matching);
  spdlog::debug("frame {}: local map {} kfs {} points, {} in view, {} new matches", frame.id, keyframes_.size(),
                points_.size(), candidates.size(), found);
  return found;
}

std::vector<ProjectedPoint> LocalMap::inView(const map::Frame& frame) const {
  std::vector<ProjectedPoint> candidates;
  candidates.reserve(points_.size());
  for (const auto& p : points_) {
    ProjectedPoint pp;
    if (p && !p->isBad() && projectIntoFrame(frame, p, 0.5, pp)) candidates.push_back(std::move(pp));
  }
  return candidates;
}

}  // namespace amos::tracking
