#pragma once
// Loop closing for one keyframe at a time (ORB-SLAM2's LoopClosing::CorrectLoop, SE(3) for RGB-D):
//   1. detect and verify a loop (loop_detector.h);
//   2. move the current keyframe's covisible neighbourhood, and the points it sees, rigidly onto the loop side;
//   3. fuse the loop side's points into that neighbourhood (duplicates across the loop become one point), which
//      creates the loop links in the covisibility graph;
//   4. optimise the essential graph (spanning tree, strong covisibility links, all loop links) and move every
//      map point with its reference keyframe.
// Runs in the local-mapping thread after a keyframe has been processed, so mapping is paused by construction;
// tracking waits on the map lock only while the correction is written (the pose graph is small).
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "amos/loop/loop_detector.h"
#include "amos/loop/pose_graph.h"
#include "amos/map/map.h"
#include "amos/match/fuse.h"

namespace amos::loop {

struct LoopClosingOptions {
  bool enabled = true;             // Loop.enabled
  int essential_min_weight = 100;  // Loop.essentialMinWeight: covisibility links kept in the essential graph (ORB-SLAM2: 100)
  // Loop.bagOfWords: loop candidates from the bag-of-words database (when there is a vocabulary) instead of the
  // thumbnails (a viewpoint-sensitive signature, kept for maps without a vocabulary).
  bool bag_of_words = true;
  // Loop.globalBundleAdjustment: after a closure, a bundle adjustment of the whole map (every keyframe and point,
  // the first keyframe fixed), as ORB-SLAM2 does. Run by the system in the mapping thread (mapping/
  // local_bundle_adjustment.h), so no keyframe is made meanwhile; tracking goes on, locked out only while the
  // result is written.
  bool global_bundle_adjustment = true;
  LoopDetectorOptions detector;
  PoseGraphOptions pose_graph;
  match::FusionOptions fusion;   // projection fusion of the loop points (Mapping.fuse* by default)
  void check() const;
};

struct LoopClosureReport {
  map::KeyFrameId current = map::kNoKeyFrame, loop = map::kNoKeyFrame;
  int inliers = 0, fused = 0;
  double correction_m = 0, correction_deg = 0;  // how far the current keyframe moved
  double pose_graph_ms = 0;
  int pose_graph_edges = 0, loop_edges = 0, pose_graph_iterations = 0;
  double pose_graph_initial_cost = 0, pose_graph_final_cost = 0;
};

class LoopCloser {
 public:
  // places: the keyframes' bag-of-words database for loop candidates (null: thumbnails, see loop_detector.h).
  LoopCloser(const LoopClosingOptions& options, std::shared_ptr<map::Map> map,
             std::shared_ptr<const place::KeyFrameDatabase> places = nullptr);

  // Looks for a loop at `kf` and closes it. Returns the closure when one was made.
  std::optional<LoopClosureReport> process(const map::KeyFramePtr& kf);
  // The loops closed so far (a copy: safe to call from another thread).
  std::vector<LoopClosureReport> closures() const;

 private:
  void correct(const LoopCandidate& loop, LoopClosureReport& report);

  LoopClosingOptions options_;
  std::shared_ptr<map::Map> map_;
  std::shared_ptr<const place::KeyFrameDatabase> places_;
  map::KeyFrameId last_loop_kf_ = map::kNoKeyFrame;
  LoopConsistency consistency_;
  std::vector<std::pair<map::KeyFrameId, map::KeyFrameId>> loop_edges_;  // kept in every later pose graph
  mutable std::mutex closures_mutex_;
  std::vector<LoopClosureReport> closures_;
};

}  // namespace amos::loop
