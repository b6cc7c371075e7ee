#pragma once
// Relocalisation of a lost frame: candidate keyframes come from the bag-of-words database when there is one
// (place/; grouped by covisibility as ORB-SLAM2 does, map/place_candidates.h), else they are ranked by the
// similarity of their thumbnails (small blurred images, as in PTAM). The best few are matched to the frame by
// brute-force descriptor matching, and each candidate pose comes from EPnP RANSAC, refined by pose optimisation
// and a projection search for more matches (the ORB-SLAM2 recipe).
#include "amos/geometry/pnp_ransac.h"
#include "amos/geometry/pose_optimizer.h"
#include "amos/map/frame.h"
#include "amos/map/map.h"
#include "amos/match/matching_options.h"
#include "amos/place/keyframe_database.h"

namespace amos::tracking {

struct RelocalizerOptions {
  int num_candidates = 8;          // keyframes tried, best thumbnails first
  int min_matches = 15;            // brute-force matches needed to try PnP on a keyframe
  float match_ratio = 0.75f;       // Lowe ratio for those matches
  int min_inliers = 50;            // inliers needed to accept a pose
  geometry::PnpRansacOptions pnp;  // reprojection threshold, iterations, seed
  void check() const;
};

class Relocalizer {
 public:
  // places: the keyframes' bag-of-words database (null: thumbnails rank the keyframes).
  Relocalizer(const RelocalizerOptions& options, const match::MatchingOptions& matching,
              const geometry::PoseOptimizerOptions& pose,
              std::shared_ptr<const place::KeyFrameDatabase> places = nullptr);

  // On success sets frame.T_cw and frame.map_points/outlier (inliers only) and returns the keyframe used.
  // Call with Map::mutex() held (shared).
  map::KeyFramePtr relocalize(map::Frame& frame, const map::Map& map) const;

 private:
  // Pose optimisation on the frame's matches; clears outliers, returns inliers.
  int optimize(map::Frame& frame) const;
  // The keyframes to try, best first.
  std::vector<map::KeyFramePtr> candidates(const map::Frame& frame, const map::Map& map) const;

  RelocalizerOptions options_;
  match::MatchingOptions matching_;
  geometry::PoseOptimizerOptions pose_;
  std::shared_ptr<const place::KeyFrameDatabase> places_;
};

}  // namespace amos::tracking
