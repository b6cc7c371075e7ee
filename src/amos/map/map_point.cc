#include "amos/map/map_point.h"

#include <algorithm>
#include <cmath>

#include "amos/map/sensor.h"

namespace amos::map {

MapPoint::MapPoint(MapPointId id, const Eigen::Vector3d& position_w, KeyFrameId reference_kf, FrameId first_frame)
    : id_(id), first_frame_(first_frame), first_kf_(reference_kf), position_(position_w), reference_kf_(reference_kf) {}

int MapPoint::indexIn(KeyFrameId kf) const {
  const auto it = observations_.find(kf);
  return it == observations_.end() ? -1 : it->second;
}

void MapPoint::addObservation(KeyFrameId kf, int index, bool with_depth) {
  if (!observations_.emplace(kf, index).second) return;
  num_obs_ += with_depth ? 2 : 1;
}

bool MapPoint::eraseObservation(KeyFrameId kf, bool with_depth) {
  if (observations_.erase(kf) == 0) return false;
  num_obs_ -= with_depth ? 2 : 1;
  return true;
}

void MapPoint::setNormalAndDistances(const Eigen::Vector3d& normal, double min_d, double max_d) {
  normal_ = normal;
  min_distance_ = min_d;
  max_distance_ = max_d;
}

int MapPoint::predictScale(double dist, const Sensor& sensor) const {
  if (dist <= 0 || max_distance_ <= 0) return 0;
  const double ratio = max_distance_ / dist;
  const int level = static_cast<int>(std::ceil(std::log(ratio) / sensor.logScaleFactor()));
  return std::clamp(level, 0, sensor.numLevels() - 1);
}

void MapPoint::addCountersFrom(const MapPoint& other) {
  increaseVisible(other.visible());
  increaseFound(other.found());
  increaseDynamicHits(other.dynamicHits());
  increaseMaskedViews(other.maskedViews());
}

}  // namespace amos::map
