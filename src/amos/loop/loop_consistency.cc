#include "amos/loop/loop_consistency.h"

#include <spdlog/spdlog.h>

namespace amos::loop {

namespace {

bool shareKeyFrame(const std::unordered_set<map::KeyFrameId>& a, const std::unordered_set<map::KeyFrameId>& b) {
  const auto& small = a.size() < b.size() ? a : b;
  const auto& large = a.size() < b.size() ? b : a;
  for (const map::KeyFrameId id : small)
    if (large.count(id)) return true;
  return false;
}

}  // namespace

std::vector<map::KeyFramePtr> LoopConsistency::filter(const map::Map& map,
                                                      const std::vector<map::KeyFramePtr>& candidates) {
  std::vector<map::KeyFramePtr> consistent;
  std::vector<Group> next;
  std::vector<bool> extended(groups_.size(), false);
  for (const map::KeyFramePtr& candidate : candidates) {
    Group group;
    group.keyframes.insert(candidate->id());
    for (const auto& [weight, id] : candidate->orderedConnections()) {
      if (map.keyFrame(id)) group.keyframes.insert(id);
    }
    bool enough = false, continues_some = false;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      if (!shareKeyFrame(group.keyframes, groups_[g].keyframes)) continue;
      continues_some = true;
      const int consistency = groups_[g].consistency + 1;
      // Each previous group is continued once, so one place does not multiply into many groups.
      if (!extended[g]) {
        next.push_back({group.keyframes, consistency});
        extended[g] = true;
      }
      if (consistency >= required_ && !enough) {
        consistent.push_back(candidate);
        enough = true;
      }
    }
    int reached = 0;
    for (std::size_t g = 0; g < groups_.size(); ++g)
      if (shareKeyFrame(group.keyframes, groups_[g].keyframes)) reached = std::max(reached, groups_[g].consistency + 1);
    spdlog::debug("loop consistency of candidate {}: {} (group of {} keyframes, {} previous groups)", candidate->id(),
                  reached, group.keyframes.size(), groups_.size());
    if (!continues_some) {
      next.push_back({group.keyframes, 0});
      if (required_ == 0) consistent.push_back(candidate);
    }
  }
  groups_ = std::move(next);
  return consistent;
}

}  // namespace amos::loop
