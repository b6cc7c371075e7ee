#pragma once
// What tracking needs from local mapping, as an interface so that tracking does not depend on the mapping module
// (mapping::LocalMapper implements it; tests can use a plain recorder).
#include <cstddef>
#include <vector>

#include "amos/map/keyframe.h"
#include "amos/map/map_point.h"

namespace amos::tracking {

class KeyFrameSink {
 public:
  virtual ~KeyFrameSink() = default;
  // Hands over a keyframe already in the map, with the points tracking created for it from depth.
  virtual void insertKeyFrame(const map::KeyFramePtr& kf, std::vector<map::MapPointPtr> new_points) = 0;
  // True when the mapper has nothing queued and is not processing (ORB-SLAM2's AcceptKeyFrames()).
  virtual bool isIdle() const = 0;
  virtual std::size_t queuedKeyFrames() const = 0;
  // Asks a running local bundle adjustment to stop early (a new keyframe is coming).
  virtual void interruptBundleAdjustment() = 0;
};

}  // namespace amos::tracking
