#include "amos/tracking/local_map_refinement.h"

#include "amos/match/pose_from_matches.h"

namespace amos::tracking {

LocalMapRefinement refineWithLocalMap(map::Frame& frame, LocalMap& local_map, const map::Map& map,
                                      const LocalMapSearch& search, const TrackerOptions& options) {
  LocalMapRefinement result;
  result.reference = local_map.update(frame, map, options.max_local_keyframes);
  local_map.searchUnmatched(frame, search.radius, options.matching);
  match::optimizeFramePose(frame, options.pose);
  result.inliers = countFoundInliers(frame);
  result.tracked = result.inliers >= search.min_inliers;
  return result;
}

int countFoundInliers(const map::Frame& frame) {
  int inliers = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto& p = frame.map_points[i];
    if (!p || frame.outlier[i]) continue;
    p->increaseFound();
    if (p->numObservations() > 0) ++inliers;
  }
  return inliers;
}

}  // namespace amos::tracking
