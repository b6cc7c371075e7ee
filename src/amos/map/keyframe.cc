#include "amos/map/keyframe.h"

#include <algorithm>

namespace amos::map {

KeyFrame::KeyFrame(KeyFrameId id, const Frame& frame)
    : id_(id),
      frame_id_(frame.id),
      timestamp_(frame.timestamp),
      features_(frame.features),
      sensor_(frame.sensor),
      thumbnail_(frame.thumbnail),
      T_cw_(frame.T_cw),
      map_points_(frame.map_points) {}

int KeyFrame::trackedMapPoints(int min_obs) const {
  int n = 0;
  for (const auto& p : map_points_) {
    if (!p || p->isBad()) continue;
    if (min_obs > 0 && p->numObservations() < min_obs) continue;
    ++n;
  }
  return n;
}

double KeyFrame::medianSceneDepth() const {
  std::vector<double> depths;
  depths.reserve(map_points_.size());
  const Eigen::Vector3d row = T_cw_.linear().row(2).transpose();
  const double tz = T_cw_.translation().z();
  for (const auto& p : map_points_) {
    if (p && !p->isBad()) depths.push_back(row.dot(p->position()) + tz);
  }
  if (depths.empty()) return -1;
  auto mid = depths.begin() + depths.size() / 2;
  std::nth_element(depths.begin(), mid, depths.end());
  return *mid;
}

int KeyFrame::weight(KeyFrameId other) const {
  const auto it = weights_.find(other);
  return it == weights_.end() ? 0 : it->second;
}

std::vector<KeyFrameId> KeyFrame::bestCovisibles(std::size_t n) const {
  std::vector<KeyFrameId> out;
  for (std::size_t i = 0; i < ordered_.size() && i < n; ++i) out.push_back(ordered_[i].second);
  return out;
}

std::vector<KeyFrameId> KeyFrame::covisiblesWithWeight(int min_weight) const {
  std::vector<KeyFrameId> out;
  for (const auto& [w, id] : ordered_) {
    if (w < min_weight) break;
    out.push_back(id);
  }
  return out;
}

void KeyFrame::setConnection(KeyFrameId other, int weight) {
  weights_[other] = weight;
  reorder();
}

void KeyFrame::eraseConnection(KeyFrameId other) {
  if (weights_.erase(other)) reorder();
}

void KeyFrame::setConnections(std::map<KeyFrameId, int> weights) {
  weights_ = std::move(weights);
  reorder();
}

void KeyFrame::reorder() {
  ordered_.clear();
  ordered_.reserve(weights_.size());
  for (const auto& [id, w] : weights_) ordered_.emplace_back(w, id);
  std::sort(ordered_.begin(), ordered_.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
}

}  // namespace amos::map
