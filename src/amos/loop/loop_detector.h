#pragma once
// Loop detection (ORB-SLAM2's DetectLoop + ComputeSim3, for RGB-D where scale is observed, so SE(3)):
//   1. candidates: keyframes not connected to the current one in the covisibility graph, at least as similar to
//      the current keyframe as its least similar covisible neighbour (ORB-SLAM2's relative test), best first. The
//      similarity is that of the bag-of-words vectors when there is a database (grouped by covisibility,
//      map/place_candidates.h), else that of the thumbnails;
//   2. temporal consistency (loop_consistency.h): only candidates that candidates of the previous keyframes also
//      pointed at go on (with min_inliers); with single_keyframe_inliers the others go on too, held to that
//      stricter count;
//   3. geometric verification: brute-force descriptor matches to the candidate's map points, PnP RANSAC,
//      pose optimisation, then the points of the candidate's whole neighbourhood projected with that pose;
//      the loop is accepted with at least `min_inliers` inliers after the final optimisation.
// Pure reading of the map: call with Map::mutex() held (shared is enough).
#include <vector>

#include "amos/geometry/pnp_ransac.h"
#include "amos/loop/loop_consistency.h"
#include "amos/geometry/pose_optimizer.h"
#include "amos/map/map.h"
#include "amos/match/matching_options.h"
#include "amos/place/keyframe_database.h"

namespace amos::loop {

struct LoopDetectorOptions {
  int min_keyframes = 10;     // Loop.minKeyFrames: no loop search in a map smaller than this (ORB-SLAM2: 10)
  int min_keyframe_gap = 10;  // Loop.minKeyFrameGap: keyframes between two loop closures (ORB-SLAM2: 10)
  int candidates = 5;         // Loop.candidates: candidates verified per keyframe, best thumbnails first
  int min_matches = 20;       // Loop.minMatches: descriptor matches to attempt PnP (ORB-SLAM2 SearchByBoW: 20)
  float match_ratio = 0.75f;  // Loop.matchRatio: Lowe ratio of those matches
  // Loop.minInliers: inliers after projecting the loop neighbourhood and optimising. A false loop corrupts the
  // whole map, so this is stricter than relocalisation (50) and ORB-SLAM2's 40 matches.
  int min_inliers = 80;
  // Loop.consistency: consecutive keyframes whose candidates must agree before a candidate is verified
  // (loop_consistency.h; ORB-SLAM2: 3). 0 = off. With single_keyframe_inliers equal to min_inliers (the default)
  // it gates nothing: every candidate is verified and held to the same bar (single_keyframe_inliers 0 restores
  // ORB-SLAM2's rule).
  int consistency = 3;
  // Loop.singleKeyFrameInliers: a candidate the temporal test has not (yet) confirmed is still verified, and accepted
  // on this keyframe alone when its verification finds at least this many inliers (0 = never: only consistent
  // candidates are verified, ORB-SLAM2's rule). The temporal test counts keyframes, so it can only confirm a place
  // the camera stays at for consistency + 1 keyframes; when keyframes are sparse (one per 20-70 frames on the
  // synthetic static_loop room lap) the revisit holds one keyframe: there the bag of words ranks the lap's first
  // keyframes top at the last keyframe, but no earlier keyframe pointed there, so ORB-SLAM2's rule closed no loop
  // on any of seeds 1-8. The same geometric bar as a consistent candidate's (min_inliers, twice ORB-SLAM2's 40
  // after projection) then decides: the single keyframes verified with 95-273 inliers. A higher bar (160) left 4
  // of those 8 laps open.
  int single_keyframe_inliers = 80;
  geometry::PnpRansacOptions pnp;       // reprojection threshold, iterations, seed
  geometry::PoseOptimizerOptions pose;  // robust pose refinement
  match::MatchingOptions matching;
  void check() const;
};

struct LoopCandidate {
  map::KeyFramePtr current, loop;
  core::SE3 T_cw_corrected = core::SE3::Identity();  // pose of `current` consistent with the loop side
  // Per keypoint of `current`: the loop-side map point it matched (null when none), inliers only.
  std::vector<map::MapPointPtr> matches;
  std::vector<map::KeyFramePtr> loop_keyframes;  // the loop keyframe and its covisible neighbours
  std::vector<map::MapPointPtr> loop_points;      // their map points
  int inliers = 0;
};

// Refines `frame`'s pose (a keyframe seen as a frame, with a good initial pose) against the map points of
// `keyframes`: projection search, then robust pose optimisation. Returns the inliers; matches are left in
// frame.map_points. Used to verify a loop and to measure the loop side's pose of each keyframe near the loop.
int localizeAgainst(map::Frame& frame, const std::vector<map::KeyFramePtr>& keyframes,
                    const LoopDetectorOptions& options);
// A keyframe as a frame to be localised (features, sensor, thumbnail, current pose; no matches).
map::Frame frameOf(const map::KeyFrame& kf);

// Returns the verified loop of `current`, or nothing. `last_loop_kf` is the id of the keyframe that closed the
// previous loop (kNoKeyFrame when none). `consistency`: the temporal test's state, advanced by one keyframe
// (null = no test: every candidate is verified at once). `places`: the keyframes' bag-of-words database (null:
// thumbnails).
std::optional<LoopCandidate> detectLoop(const map::Map& map, const map::KeyFramePtr& current,
                                        map::KeyFrameId last_loop_kf, const LoopDetectorOptions& options,
                                        LoopConsistency* consistency = nullptr,
                                        const place::KeyFrameDatabase* places = nullptr);

}  // namespace amos::loop
