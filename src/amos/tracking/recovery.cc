#include "amos/tracking/recovery.h"

#include <spdlog/spdlog.h>

#include "amos/match/pose_from_matches.h"
#include "amos/tracking/matching.h"

namespace amos::tracking {

bool recoverNearPredictions(map::Frame& frame, const std::vector<core::SE3>& predictions, const LocalMap& local_map,
                            const TrackerOptions& options) {
  for (const core::SE3& T : predictions) {
    frame.resetMatches();
    frame.setPose(T);
    const std::vector<ProjectedPoint> candidates = local_map.inView(frame);
    const int found = searchLocalPoints(frame, candidates, options.recovery_search_radius, options.matching);
    spdlog::debug("frame {}: recovery search: {} of {} local points in view matched", frame.id, found,
                  candidates.size());
    if (found < options.reloc_min_inliers) continue;
    // The wide window lets wrong matches in, and the prediction may be degrees off: PnP RANSAC on the matches
    // (as the relocaliser does) rather than a pose optimisation started at the prediction.
    const std::vector<map::MapPointPtr> matches = frame.map_points;
    const int pnp_inliers = match::poseFromMatchesByPnp(frame, matches, options.relocalization.pnp);
    if (pnp_inliers < options.reloc_min_inliers) continue;
    const int inliers = match::optimizeFramePoseDroppingOutliers(frame, options.pose);
    spdlog::debug("frame {}: recovery search {} matches, {} inliers", frame.id, found, inliers);
    if (inliers >= options.reloc_min_inliers) return true;
  }
  frame.resetMatches();
  return false;
}

}  // namespace amos::tracking
