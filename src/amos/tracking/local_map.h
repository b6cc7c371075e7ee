#pragma once
// The part of the map around the current frame (ORB-SLAM2's local map, stella_vslam's local_map_updater): the
// keyframes that observe the frame's matched points, with a covisible neighbour, a child and the parent of each,
// and the points those keyframes see. Kept from frame to frame (the recovery after a loss searches the last one);
// its buffers are reused. Call with Map::mutex() held (shared).
#include <vector>

#include "amos/map/frame.h"
#include "amos/map/keyframe.h"
#include "amos/map/map.h"
#include "amos/map/map_point.h"
#include "amos/match/matching_options.h"
#include "amos/tracking/id_marks.h"
#include "amos/tracking/matching.h"

namespace amos::tracking {

class LocalMap {
 public:
  // Rebuilds the local map around the frame's matches (matches to bad points are dropped); at most about
  // max_keyframes keyframes. Returns the keyframe that shares the most points with the frame (null: none).
  map::KeyFramePtr update(map::Frame& frame, const map::Map& map, int max_keyframes);
  // Starts over from one keyframe (the map's first).
  void reset(const map::KeyFramePtr& kf);

  // Projects the local points the frame has not matched into it, counts them as visible (and, with a dynamic
  // mask, their mask evidence, dynamic_evidence.h) and searches matches for them within th (matching.h).
  // Returns the new matches.
  int searchUnmatched(map::Frame& frame, double th, const match::MatchingOptions& matching) const;
  // The good local points in view of the frame's pose, counting nothing.
  std::vector<ProjectedPoint> inView(const map::Frame& frame) const;

  const std::vector<map::KeyFramePtr>& keyFrames() const { return keyframes_; }
  const std::vector<map::MapPointPtr>& points() const { return points_; }

 private:
  // The keyframes observing the frame's points, by id; returns the one observing the most.
  map::KeyFramePtr addObservingKeyFrames(map::Frame& frame, const map::Map& map);
  void addNeighbours(const map::Map& map, int max_keyframes);
  void collectPoints();

  std::vector<map::KeyFramePtr> keyframes_;
  std::vector<map::MapPointPtr> points_;
  // Per-frame scratch, kept so that no frame allocates it again: observation counts by keyframe id (zero between
  // calls) and the ids counted, the keyframes and points taken, the frame's own matched points.
  std::vector<int> observation_counts_;
  std::vector<map::KeyFrameId> observed_ids_;
  IdMarks keyframe_marks_, point_marks_;
  mutable IdMarks frame_point_marks_;
};

}  // namespace amos::tracking
