#include "amos/tracking/keyframe_insertion.h"

#include <mutex>

#include "amos/tracking/depth_order.h"

namespace amos::tracking {

NewKeyFrame insertFirstKeyFrame(map::Map& map, map::Frame& frame, PhotometricRefiner* photometric) {
  const map::FrameFeatures& f = *frame.features;
  NewKeyFrame out;
  std::unique_lock lock(map.mutex());
  out.kf = std::make_shared<map::KeyFrame>(map.newKeyFrameId(), frame);
  map.addKeyFrame(out.kf);
  if (photometric) photometric->addKeyFrame(out.kf->id(), frame);
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!f.hasDepth(static_cast<int>(i))) continue;
    auto p = map.createMapPoint(frame.unproject(static_cast<int>(i)), out.kf, static_cast<int>(i), frame.id);
    frame.map_points[i] = p;
    out.new_points.push_back(p);
  }
  return out;
}

NewKeyFrame insertKeyFrame(map::Map& map, map::Frame& frame, const KeyFrameInsertion& insertion) {
  NewKeyFrame out;
  std::unique_lock lock(map.mutex());
  out.kf = std::make_shared<map::KeyFrame>(map.newKeyFrameId(), frame);
  const map::KeyFramePtr& kf = out.kf;
  map.addKeyFrame(kf);
  if (insertion.photometric) insertion.photometric->addKeyFrame(kf->id(), frame);
  if (insertion.photometric_link) kf->setPhotometricLink(*insertion.photometric_link);
  for (int i = 0; i < kf->size(); ++i) {
    const map::MapPointPtr p = kf->mapPoint(i);
    if (!p) continue;
    if (p->isBad() || p->isObservedBy(kf->id())) {
      kf->clearMapPoint(i);
      frame.map_points[i].reset();
      continue;
    }
    map.addObservation(p, kf, i);
  }
  const auto by_depth = keypointsByDepth(*frame.features, frame.sensor->closeDepth(), insertion.new_points_min);
  int n = 0;
  for (const auto& [z, i] : by_depth) {
    if (!frame.map_points[i]) {
      auto p = map.createMapPoint(frame.unproject(i), kf, i, frame.id);
      frame.map_points[i] = p;
      out.new_points.push_back(std::move(p));
    }
    ++n;
    if (z > frame.sensor->closeDepth() && n > insertion.new_points_min) break;
  }
  return out;
}

}  // namespace amos::tracking
