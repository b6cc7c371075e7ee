#pragma once
// Local bundle adjustment around a keyframe (ORB-SLAM2's LocalBundleAdjustment): the keyframe and its covisible
// keyframes are optimised together with every point they see; other keyframes that see those points are held
// fixed, as is the map's first keyframe. The problem is copied out under a shared lock, solved without any lock
// (tracking keeps running) and written back under an exclusive lock, dropping the observations that end up as
// outliers.
#include <atomic>

#include "amos/map/map.h"
#include "amos/mapping/bundle_adjustment.h"

namespace amos::mapping {

struct LocalBaStats {
  int local_keyframes = 0, fixed_keyframes = 0, points = 0, observations = 0;
  int outliers_removed = 0;
  bool aborted = false;
};

LocalBaStats runLocalBundleAdjustment(map::Map& map, const map::KeyFramePtr& keyframe,
                                      const BundleAdjustmentOptions& options, const std::atomic<bool>* abort);

}  // namespace amos::mapping
