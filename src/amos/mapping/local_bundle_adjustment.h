#pragma once
// Bundle adjustment of the map: local, around a keyframe (ORB-SLAM2's LocalBundleAdjustment: the keyframe and its
// covisible keyframes are optimised together with every point they see; other keyframes that see those points are
// held fixed, as is the map's first keyframe), and global, of the whole map after a loop closure. The problem is
// copied out under a shared lock, solved without any lock (tracking keeps running) and written back under an
// exclusive lock, dropping the observations that end up as outliers.
#include <atomic>

#include "amos/map/map.h"
#include "amos/mapping/bundle_adjustment.h"

namespace amos::mapping {

struct BaStats {
  int adjusted_keyframes = 0, fixed_keyframes = 0, points = 0, observations = 0;
  int outliers_removed = 0;
  bool aborted = false;
};

BaStats runLocalBundleAdjustment(map::Map& map, const map::KeyFramePtr& keyframe,
                                      const BundleAdjustmentOptions& options, const std::atomic<bool>* abort);

// Global bundle adjustment (ORB-SLAM2 runs one after every loop closure): every keyframe and every point, the
// map's first keyframe held fixed; same locking as the local one. The pose graph moves keyframes as rigid bodies
// along the graph; this lets the points and poses on both sides of the loop agree with their observations.
BaStats runGlobalBundleAdjustment(map::Map& map, const BundleAdjustmentOptions& options,
                                       const std::atomic<bool>* abort);

}  // namespace amos::mapping
