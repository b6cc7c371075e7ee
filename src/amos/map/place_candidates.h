#pragma once
// Keyframes that may show the same place as a query, from the bag-of-words database (place/): the selection
// ORB-SLAM2 makes for relocalisation and loop detection (Mur-Artal et al., T-RO 2015, Sec. V-C and VI-A):
//   1. keyframes sharing words with the query, with at least min_common_ratio x the most common words;
//   2. their similarity to the query, at least min_score;
//   3. each one's covisibility group (itself and its 10 best covisible keyframes among the candidates) scores the
//      sum of their similarities, and is represented by its best-scoring member: a place seen from several
//      keyframes beats a lone look-alike;
//   4. the groups scoring at least group_ratio x the best group, best first, at most max_candidates.
// Call with Map::mutex() held (shared).
#include <functional>
#include <utility>
#include <vector>

#include "amos/map/map.h"
#include "amos/place/keyframe_database.h"

namespace amos::map {

struct PlaceQueryOptions {
  double min_common_ratio = 0.8;
  double min_score = 0;
  double group_ratio = 0.75;
  std::size_t max_candidates = 8;
};

// (group score, keyframe), best first. `skip` rejects keyframes (e.g. the query's own neighbours); keyframes no
// longer in the map are skipped too.
std::vector<std::pair<double, KeyFramePtr>> placeCandidates(const Map& map, const place::KeyFrameDatabase& places,
                                                             const place::BowVector& query,
                                                             const PlaceQueryOptions& options,
                                                             const std::function<bool(KeyFrameId)>& skip = {});

}  // namespace amos::map
