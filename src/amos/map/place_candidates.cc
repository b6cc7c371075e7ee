#include "amos/map/place_candidates.h"

#include <algorithm>
#include <set>
#include <unordered_map>

namespace amos::map {

std::vector<std::pair<double, KeyFramePtr>> placeCandidates(const Map& map, const place::KeyFrameDatabase& places,
                                                             const place::BowVector& query,
                                                             const PlaceQueryOptions& options,
                                                             const std::function<bool(KeyFrameId)>& skip) {
  const std::vector<place::PlaceMatch> matches = places.query(query, options.min_common_ratio, [&](place::EntryId id) {
    if (skip && skip(id)) return true;
    const KeyFramePtr kf = map.keyFrame(id);
    return !kf || kf->isBad();
  });
  std::unordered_map<KeyFrameId, double> score;
  for (const place::PlaceMatch& m : matches) {
    if (m.score >= options.min_score) score[m.id] = m.score;
  }
  std::vector<std::pair<double, KeyFrameId>> groups;
  double best_group = 0;
  for (const place::PlaceMatch& m : matches) {  // best first: deterministic order
    if (!score.count(m.id)) continue;
    const KeyFramePtr kf = map.keyFrame(m.id);
    double group = m.score, best_score = m.score;
    KeyFrameId best = m.id;
    for (const KeyFrameId n : kf->bestCovisibles(10)) {
      const auto it = score.find(n);
      if (it == score.end()) continue;
      group += it->second;
      if (it->second > best_score) {
        best_score = it->second;
        best = n;
      }
    }
    groups.emplace_back(group, best);
    best_group = std::max(best_group, group);
  }
  std::stable_sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::pair<double, KeyFramePtr>> out;
  std::set<KeyFrameId> taken;
  for (const auto& [group, id] : groups) {
    if (group < options.group_ratio * best_group || out.size() >= options.max_candidates) break;
    if (!taken.insert(id).second) continue;
    out.emplace_back(group, map.keyFrame(id));
  }
  return out;
}

}  // namespace amos::map
