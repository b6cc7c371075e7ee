#include "amos/map/map.h"

#include <algorithm>
#include <limits>

#include "amos/core/error.h"
#include "amos/feature/descriptor_distance.h"

namespace amos::map {

namespace {
bool hasDepth(const KeyFrame& kf, int index) { return kf.features().depth[index] > 0; }
}  // namespace

void Map::addKeyFrame(const KeyFramePtr& kf) {
  keyframes_[kf->id()] = kf;
  if (first_kf_ == kNoKeyFrame) first_kf_ = kf->id();
}

void Map::addMapPoint(const MapPointPtr& p) { points_[p->id()] = p; }

MapPointPtr Map::createMapPoint(const Eigen::Vector3d& position_w, const KeyFramePtr& kf, int index, FrameId frame) {
  auto p = std::make_shared<MapPoint>(newMapPointId(), position_w, kf->id(), frame);
  addObservation(p, kf, index);
  updateDescriptor(p);
  updateNormalAndDepth(p);
  addMapPoint(p);
  return p;
}

KeyFramePtr Map::keyFrame(KeyFrameId id) const {
  const auto it = keyframes_.find(id);
  return it == keyframes_.end() ? nullptr : it->second;
}

MapPointPtr Map::mapPoint(MapPointId id) const {
  const auto it = points_.find(id);
  return it == points_.end() ? nullptr : it->second;
}

std::vector<KeyFramePtr> Map::keyFrames() const {
  std::vector<KeyFramePtr> out;
  out.reserve(keyframes_.size());
  for (const auto& [id, kf] : keyframes_) out.push_back(kf);
  return out;
}

std::vector<MapPointPtr> Map::mapPoints() const {
  std::vector<MapPointPtr> out;
  out.reserve(points_.size());
  for (const auto& [id, p] : points_) out.push_back(p);
  return out;
}

void Map::addObservation(const MapPointPtr& p, const KeyFramePtr& kf, int index) {
  kf->setMapPoint(index, p);
  p->addObservation(kf->id(), index, hasDepth(*kf, index));
}

void Map::eraseObservation(const MapPointPtr& p, KeyFrameId kf_id) {
  const int index = p->indexIn(kf_id);
  if (index < 0) return;
  const KeyFramePtr kf = keyFrame(kf_id);
  const bool depth = kf ? hasDepth(*kf, index) : false;
  p->eraseObservation(kf_id, depth);
  if (kf && kf->mapPoint(index) == p) kf->clearMapPoint(index);
  if (p->referenceKeyFrame() == kf_id && !p->observations().empty()) {
    p->setReferenceKeyFrame(p->observations().begin()->first);
  }
  if (p->numObservations() <= 2) setMapPointBad(p);
}

void Map::setMapPointBad(const MapPointPtr& p) {
  p->setBadFlag();
  const auto observations = p->observations();
  for (const auto& [kf_id, index] : observations) {
    const KeyFramePtr kf = keyFrame(kf_id);
    p->eraseObservation(kf_id, kf ? hasDepth(*kf, index) : false);
    if (kf && kf->mapPoint(index) == p) kf->clearMapPoint(index);
  }
  points_.erase(p->id());
}

void Map::replaceMapPoint(const MapPointPtr& old_p, const MapPointPtr& new_p) {
  if (!old_p || !new_p || old_p == new_p || old_p->id() == new_p->id()) return;
  const auto observations = old_p->observations();
  old_p->setBadFlag();
  old_p->setReplacedBy(new_p);
  for (const auto& [kf_id, index] : observations) {
    const KeyFramePtr kf = keyFrame(kf_id);
    const bool depth = kf ? hasDepth(*kf, index) : false;
    old_p->eraseObservation(kf_id, depth);
    if (!kf) continue;
    if (!new_p->isObservedBy(kf_id)) {
      kf->setMapPoint(index, new_p);
      new_p->addObservation(kf_id, index, depth);
    } else if (kf->mapPoint(index) == old_p) {
      kf->clearMapPoint(index);
    }
  }
  new_p->addCountersFrom(*old_p);
  points_.erase(old_p->id());
  updateDescriptor(new_p);
}

void Map::updateDescriptor(const MapPointPtr& p) {
  std::vector<const std::uint8_t*> descs;
  for (const auto& [kf_id, index] : p->observations()) {
    const KeyFramePtr kf = keyFrame(kf_id);
    if (!kf || kf->isBad()) continue;
    descs.push_back(kf->features().descriptors.ptr<std::uint8_t>(index));
  }
  if (descs.empty()) return;
  const std::size_t n = descs.size();
  std::vector<int> dist(n * n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      dist[i * n + j] = dist[j * n + i] = feature::hammingDistance(descs[i], descs[j]);
    }
  }
  int best_median = std::numeric_limits<int>::max();
  std::size_t best = 0;
  std::vector<int> row(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::copy(dist.begin() + i * n, dist.begin() + (i + 1) * n, row.begin());
    std::nth_element(row.begin(), row.begin() + (n - 1) / 2, row.end());
    const int median = row[(n - 1) / 2];
    if (median < best_median) {
      best_median = median;
      best = i;
    }
  }
  p->setDescriptor(cv::Mat(1, 32, CV_8U, const_cast<std::uint8_t*>(descs[best])));
}

void Map::updateNormalAndDepth(const MapPointPtr& p) {
  if (p->observations().empty()) return;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  int n = 0;
  for (const auto& [kf_id, index] : p->observations()) {
    const KeyFramePtr kf = keyFrame(kf_id);
    if (!kf) continue;
    const Eigen::Vector3d d = p->position() - kf->center();
    if (d.norm() > 0) normal += d.normalized();
    ++n;
  }
  KeyFramePtr ref = keyFrame(p->referenceKeyFrame());
  if (!ref || !p->isObservedBy(ref->id())) {
    ref = keyFrame(p->observations().begin()->first);
    if (!ref) return;
    p->setReferenceKeyFrame(ref->id());
  }
  const double dist = (p->position() - ref->center()).norm();
  const int level = ref->features().keys[p->indexIn(ref->id())].octave;
  const Sensor& s = ref->sensor();
  const double max_d = dist * s.scales()[std::clamp(level, 0, s.numLevels() - 1)];
  const double min_d = max_d / s.scales().back();
  p->setNormalAndDistances(n > 0 && normal.norm() > 0 ? Eigen::Vector3d(normal.normalized()) : Eigen::Vector3d::Zero(),
                           min_d, max_d);
}

void Map::updateConnections(const KeyFramePtr& kf) {
  std::map<KeyFrameId, int> counts;
  for (const auto& p : kf->mapPoints()) {
    if (!p || p->isBad()) continue;
    for (const auto& [other, index] : p->observations()) {
      if (other != kf->id()) ++counts[other];
    }
  }
  if (counts.empty()) return;
  std::map<KeyFrameId, int> kept;
  KeyFrameId best_id = kNoKeyFrame;
  int best_w = 0;
  for (const auto& [other, w] : counts) {
    if (w > best_w) {
      best_w = w;
      best_id = other;
    }
    if (w >= options_.min_weight) kept[other] = w;
  }
  if (kept.empty()) kept[best_id] = best_w;
  for (const auto& [other, w] : kept) {
    if (const KeyFramePtr o = keyFrame(other)) o->setConnection(kf->id(), w);
  }
  // Links that fell below the threshold disappear on the other side too.
  for (const auto& [other, w] : kf->connectionWeights()) {
    if (!kept.count(other)) {
      if (const KeyFramePtr o = keyFrame(other)) o->eraseConnection(kf->id());
    }
  }
  kf->setConnections(kept);
  if (!kf->hasFirstConnection() && kf->id() != first_kf_) {
    // Spanning-tree parent: the most covisible *older* keyframe. Tracking inserts keyframes while mapping still
    // works on earlier ones, so a newer keyframe may already share the most points; taking it could make two
    // keyframes each other's parent, and the parent chain of a removed keyframe (keyFramePose) would never end.
    // Parents older than their children keep the tree acyclic by construction.
    KeyFrameId parent = first_kf_;
    for (const auto& [w, id] : kf->orderedConnections()) {
      if (id < kf->id()) {
        parent = id;
        break;
      }
    }
    kf->setParent(parent);
    if (const KeyFramePtr pk = keyFrame(parent)) pk->addChild(kf->id());
    kf->markFirstConnectionDone();
  }
}

void Map::setKeyFrameBad(const KeyFramePtr& kf) {
  if (kf->id() == first_kf_ || kf->isBad()) return;
  for (const auto& [other, w] : kf->connectionWeights()) {
    if (const KeyFramePtr o = keyFrame(other)) o->eraseConnection(kf->id());
  }
  for (int i = 0; i < kf->size(); ++i) {
    if (const MapPointPtr p = kf->mapPoint(i)) eraseObservation(p, kf->id());
  }
  // Re-parent the children: each goes to its most covisible keyframe among the candidates (the removed
  // keyframe's parent and children already re-parented); the rest go to the parent.
  KeyFrameId parent = kf->parent();
  if (!keyFrame(parent)) parent = first_kf_;
  std::set<KeyFrameId> candidates{parent};
  std::set<KeyFrameId> children = kf->children();
  while (!children.empty()) {
    int best_w = -1;
    KeyFrameId best_child = kNoKeyFrame, best_parent = kNoKeyFrame;
    for (const KeyFrameId c : children) {
      const KeyFramePtr ck = keyFrame(c);
      if (!ck) continue;
      for (const KeyFrameId cand : candidates) {
        const int w = ck->weight(cand);
        if (w > best_w && w > 0) {
          best_w = w;
          best_child = c;
          best_parent = cand;
        }
      }
    }
    if (best_child == kNoKeyFrame) break;
    const KeyFramePtr ck = keyFrame(best_child);
    ck->setParent(best_parent);
    keyFrame(best_parent)->addChild(best_child);
    candidates.insert(best_child);
    children.erase(best_child);
  }
  for (const KeyFrameId c : children) {
    if (const KeyFramePtr ck = keyFrame(c)) {
      ck->setParent(parent);
      if (const KeyFramePtr pk = keyFrame(parent)) pk->addChild(c);
    }
  }
  RemovedKeyFrame record;
  record.parent = parent;
  if (const KeyFramePtr pk = keyFrame(parent)) {
    pk->eraseChild(kf->id());
    record.T_cp = kf->T_cw() * pk->T_wc();
  }
  removed_[kf->id()] = record;
  kf->setConnections({});
  kf->setBadFlag();
  keyframes_.erase(kf->id());
}

bool Map::knowsKeyFrame(KeyFrameId id) const { return keyframes_.count(id) || removed_.count(id); }

core::SE3 Map::keyFramePose(KeyFrameId id) const {
  core::SE3 T = core::SE3::Identity();
  // Walk up removed keyframes (bounded by their number) until a live one.
  const KeyFrameId asked = id;
  for (std::size_t guard = 0; guard <= removed_.size(); ++guard) {
    if (const KeyFramePtr kf = keyFrame(id)) return T * kf->T_cw();
    const auto it = removed_.find(id);
    if (it == removed_.end()) {
      throw core::Error("Map::keyFramePose: unknown keyframe " + std::to_string(id) +
                        (id == asked ? std::string() : " (parent chain of keyframe " + std::to_string(asked) + ")"));
    }
    T = T * it->second.T_cp;
    id = it->second.parent;
  }
  throw core::Error("Map::keyFramePose: the parent chain of removed keyframe " + std::to_string(asked) +
                    " does not reach a live keyframe (a cycle)");
}

std::vector<MapPointId> Map::dynamicPointCandidates(int min_hits, double min_ratio) const {
  std::vector<MapPointId> out;
  for (const auto& [id, p] : points_) {
    if (p->isBad() || p->dynamicHits() < min_hits) continue;
    if (p->dynamicHits() >= min_ratio * std::max(1, p->maskedViews())) out.push_back(id);
  }
  return out;
}

}  // namespace amos::map
