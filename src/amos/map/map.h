#pragma once
// The map: owns keyframes and map points (shared_ptr in id-keyed containers) and keeps the observation and
// covisibility bookkeeping consistent on both sides.
//
// Thread-safety contract (one reader-writer lock for the whole map, as ORB-SLAM2's map mutex):
//   - mutex() guards every container here and the mutable parts of KeyFrame and MapPoint.
//   - Tracking takes a shared lock while it reads the map (matching, local map) and an exclusive lock only to
//     insert a keyframe with its new points. Local mapping takes a shared lock to read and an exclusive lock for
//     each change (new points, fusion, culling, writing back bundle-adjustment results); it never holds the
//     exclusive lock while solving, so tracking never waits for bundle adjustment.
//   - Methods marked [exclusive] must be called with an exclusive lock held, [shared] with at least a shared one.
//     The Map never locks by itself, so callers can group several calls into one critical section.
#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <vector>

#include "amos/core/pose.h"
#include "amos/map/ids.h"
#include "amos/map/keyframe.h"
#include "amos/map/map_point.h"

namespace amos::map {

struct CovisibilityOptions {
  int min_weight = 15;  // covisibility links below this many shared points are dropped (best one kept)
};

class Map {
 public:
  explicit Map(CovisibilityOptions options = {}) : options_(options) {}

  std::shared_mutex& mutex() const { return mutex_; }

  // Ids come from lock-free counters so frames can be prepared before taking the lock.
  KeyFrameId newKeyFrameId() { return next_kf_id_++; }
  MapPointId newMapPointId() { return next_mp_id_++; }

  // [exclusive]
  void addKeyFrame(const KeyFramePtr& kf);
  void addMapPoint(const MapPointPtr& p);
  // New point seen in `kf` at keypoint `index` (observation added on both sides, descriptor and normal set).
  MapPointPtr createMapPoint(const Eigen::Vector3d& position_w, const KeyFramePtr& kf, int index, FrameId frame);

  // [shared]
  KeyFramePtr keyFrame(KeyFrameId id) const;
  MapPointPtr mapPoint(MapPointId id) const;
  std::vector<KeyFramePtr> keyFrames() const;  // by increasing id
  std::vector<MapPointPtr> mapPoints() const;  // by increasing id
  std::size_t numKeyFrames() const { return keyframes_.size(); }
  std::size_t numMapPoints() const { return points_.size(); }
  KeyFrameId firstKeyFrameId() const { return first_kf_; }

  // --- graph operations [exclusive] ---
  void addObservation(const MapPointPtr& p, const KeyFramePtr& kf, int index);
  // Removes the observation on both sides; a point left with <= 2 observations becomes bad (ORB-SLAM2 rule).
  void eraseObservation(const MapPointPtr& p, KeyFrameId kf);
  // Marks the point bad, removes all its observations and erases it from the map.
  void setMapPointBad(const MapPointPtr& p);
  // Fuses `old_p` into `new_p`: observations move over (unless the keyframe already sees new_p), counters add.
  void replaceMapPoint(const MapPointPtr& old_p, const MapPointPtr& new_p);
  // Recomputes the representative descriptor (smallest median distance to the others) of the point.
  void updateDescriptor(const MapPointPtr& p);
  // Mean viewing direction and scale-invariance distances from the reference keyframe.
  void updateNormalAndDepth(const MapPointPtr& p);
  // Recomputes the covisibility links of kf (both sides) and, on the first call, its spanning-tree parent.
  void updateConnections(const KeyFramePtr& kf);
  // Removes a redundant keyframe: links, observations, re-parents its children, remembers its pose relative to
  // its parent so trajectories referring to it stay valid. The first keyframe is never removed.
  void setKeyFrameBad(const KeyFramePtr& kf);

  // Current world-to-camera pose of a keyframe, also for removed ones (through the parent chain). [shared]
  core::SE3 keyFramePose(KeyFrameId id) const;
  bool knowsKeyFrame(KeyFrameId id) const;

  // Hook for the dynamic front end: good points that projected into dynamic masks at least `min_hits` times and
  // in at least `min_ratio` of the masked frames that saw them. [shared]
  std::vector<MapPointId> dynamicPointCandidates(int min_hits, double min_ratio) const;

  // A keyframe removed by culling, kept so frames that referred to it still have a pose (keyFramePose).
  struct RemovedKeyFrame {
    KeyFrameId parent = kNoKeyFrame;
    core::SE3 T_cp = core::SE3::Identity();  // pose relative to the parent at removal time
  };

  // --- saving and restoring a map (mapio/) ---
  KeyFrameId nextKeyFrameId() const { return next_kf_id_.load(); }
  MapPointId nextMapPointId() const { return next_mp_id_.load(); }
  const std::map<KeyFrameId, RemovedKeyFrame>& removedKeyFrames() const { return removed_; }  // [shared]
  // [exclusive] Only on a map being restored: its next ids (at least one past every restored id) and the
  // records of its removed keyframes.
  void restoreNextIds(KeyFrameId next_kf, MapPointId next_mp) {
    next_kf_id_ = next_kf;
    next_mp_id_ = next_mp;
  }
  void restoreRemovedKeyFrame(KeyFrameId id, const RemovedKeyFrame& record) { removed_[id] = record; }

 private:

  CovisibilityOptions options_;
  mutable std::shared_mutex mutex_;
  std::atomic<KeyFrameId> next_kf_id_{0};
  std::atomic<MapPointId> next_mp_id_{0};
  std::map<KeyFrameId, KeyFramePtr> keyframes_;
  std::map<MapPointId, MapPointPtr> points_;
  std::map<KeyFrameId, RemovedKeyFrame> removed_;
  KeyFrameId first_kf_ = kNoKeyFrame;
};

}  // namespace amos::map
