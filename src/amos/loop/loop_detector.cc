#include "amos/loop/loop_detector.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <unordered_set>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/map/place_candidates.h"
#include "amos/match/brute_force_search.h"
#include "amos/match/pose_from_matches.h"
#include "amos/match/projection_search.h"

namespace amos::loop {

void LoopDetectorOptions::check() const {
  core::requireAtLeast(min_keyframes, "min_keyframes", 2);
  core::requireAtLeast(min_keyframe_gap, "min_keyframe_gap", 0);
  core::requireAtLeast(candidates, "candidates", 1);
  core::requireAtLeast(min_matches, "min_matches", 6);
  core::requireOption(match_ratio > 0 && match_ratio <= 1, core::option(match_ratio, "match_ratio"),
                      fmt::format("must be in (0, 1], got {}", match_ratio));
  core::requireOption(min_inliers >= min_matches, core::option(min_inliers, "min_inliers"),
                      fmt::format("must be >= min_matches = {}, got {}", min_matches, min_inliers),
                      {core::option(min_matches, "min_matches")});
  core::requireAtLeast(consistency, "consistency", 0);
  core::requireOption(single_keyframe_inliers == 0 || single_keyframe_inliers >= min_inliers,
                      core::option(single_keyframe_inliers, "single_keyframe_inliers"),
                      fmt::format("must be 0 (off) or >= min_inliers = {}, got {}", min_inliers,
                                  single_keyframe_inliers),
                      {core::option(min_inliers, "min_inliers")});
  pnp.check();
  pose.check();
  matching.check();
}

map::Frame frameOf(const map::KeyFrame& kf) {
  map::Frame f;
  f.id = kf.frameId();
  f.timestamp = kf.timestamp();
  f.sensor = kf.sharedSensor();
  f.features = kf.sharedFeatures();
  f.thumbnail = kf.thumbnail();
  f.setPose(kf.T_cw());
  f.resetMatches();
  return f;
}

int localizeAgainst(map::Frame& frame, const std::vector<map::KeyFramePtr>& keyframes,
                    const LoopDetectorOptions& options) {
  for (const auto& kf : keyframes) {
    match::searchKeyFrameByProjection(frame, *kf, match::matchedPoints(frame), 10, options.matching.th_high,
                                      options.matching);
  }
  return match::optimizeFramePoseDroppingOutliers(frame, options.pose);
}

namespace {

// Keyframes not covisible with `current` whose thumbnail is at least as similar as its least similar covisible
// neighbour's, best first, at most options.candidates. `connected` receives current and its covisible keyframes.
std::vector<map::KeyFramePtr> rankCandidates(const map::Map& map, const map::KeyFramePtr& current,
                                             const LoopDetectorOptions& options,
                                             std::unordered_set<map::KeyFrameId>& connected,
                                             const place::KeyFrameDatabase* places) {
  connected = {current->id()};
  double max_neighbour_distance = 0;
  for (const auto& [w, id] : current->orderedConnections()) {
    connected.insert(id);
    if (const map::KeyFramePtr n = map.keyFrame(id)) {
      max_neighbour_distance =
          std::max(max_neighbour_distance, map::thumbnailDistance(current->thumbnail(), n->thumbnail()));
    }
  }
  if (connected.size() < 2) return {};  // no neighbour: nothing to compare similarity with

  std::vector<std::pair<double, map::KeyFramePtr>> ranked;
  if (places != nullptr) {
    const place::BowVector v = places->vector(current->id());
    if (v.empty()) return {};
    double min_score = 1;
    for (const auto& [w, id] : current->orderedConnections()) {
      const place::BowVector n = places->vector(id);
      if (!n.empty()) min_score = std::min(min_score, place::similarity(v, n));
    }
    if (spdlog::should_log(spdlog::level::debug)) {  // where the place's keyframes rank, connected or not
      std::string top;
      int shown = 0;
      for (const place::PlaceMatch& m : places->query(v, 0.0)) {
        if (m.id == current->id() || m.id > current->id()) continue;
        const map::KeyFramePtr kf = map.keyFrame(m.id);
        top += fmt::format(" {}@{}{}:{:.3f}/{}", m.id, kf ? static_cast<long>(kf->frameId()) : -1L,
                           connected.count(m.id) ? "c" : "", m.score, m.common_words);
        if (++shown == 12) break;
      }
      spdlog::debug("loop bow at keyframe {}@{}: min covisible score {:.3f} over {} neighbours; best:{}", current->id(),
                    current->frameId(), min_score, current->orderedConnections().size(), top);
    }
    map::PlaceQueryOptions query;
    query.min_score = min_score;
    query.max_candidates = static_cast<std::size_t>(options.candidates);
    std::vector<map::KeyFramePtr> out;
    std::string listed;
    for (const auto& [score, kf] : map::placeCandidates(map, *places, v, query, [&](map::KeyFrameId id) {
           return connected.count(id) > 0 || id > current->id();
         })) {
      out.push_back(kf);
      listed += fmt::format(" {}:{:.3f}", kf->id(), score);
    }
    spdlog::debug("loop bow candidates of keyframe {}:{}", current->id(), listed);
    return out;
  }
  for (const auto& kf : map.keyFrames()) {
    if (kf->isBad() || connected.count(kf->id()) || kf->id() > current->id()) continue;
    const double d = map::thumbnailDistance(current->thumbnail(), kf->thumbnail());
    if (d <= max_neighbour_distance) ranked.emplace_back(d, kf);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (ranked.size() > static_cast<std::size_t>(options.candidates)) ranked.resize(options.candidates);
  std::vector<map::KeyFramePtr> out;
  for (const auto& entry : ranked) out.push_back(entry.second);
  return out;
}

}  // namespace

std::optional<LoopCandidate> detectLoop(const map::Map& map, const map::KeyFramePtr& current,
                                        map::KeyFrameId last_loop_kf, const LoopDetectorOptions& options,
                                        LoopConsistency* consistency, const place::KeyFrameDatabase* places) {
  options.check();
  if (!current || current->isBad()) return std::nullopt;
  if (map.numKeyFrames() < static_cast<std::size_t>(options.min_keyframes)) return std::nullopt;
  if (last_loop_kf != map::kNoKeyFrame && current->id() < last_loop_kf + options.min_keyframe_gap) return std::nullopt;

  std::unordered_set<map::KeyFrameId> connected;
  std::vector<map::KeyFramePtr> candidates = rankCandidates(map, current, options, connected, places);
  // Candidates held to min_inliers; the others (not temporally consistent yet) to single_keyframe_inliers.
  std::unordered_set<map::KeyFrameId> confirmed;
  if (consistency != nullptr) {
    const std::vector<map::KeyFramePtr> consistent = consistency->filter(map, candidates);
    spdlog::debug("loop search at keyframe {}: {} candidates, {} consistent", current->id(), candidates.size(),
                  consistent.size());
    for (const auto& kf : consistent) confirmed.insert(kf->id());
    if (options.single_keyframe_inliers == 0) candidates = consistent;
  } else {
    for (const auto& kf : candidates) confirmed.insert(kf->id());
  }

  for (const map::KeyFramePtr& candidate : candidates) {
    const int needed = confirmed.count(candidate->id()) ? options.min_inliers : options.single_keyframe_inliers;
    map::Frame frame = frameOf(*current);
    int n = 0;
    std::vector<map::MapPointPtr> matches =
        match::matchFrameToKeyFrame(frame, *candidate, options.match_ratio, options.matching, &n);
    if (n < options.min_matches) {
      spdlog::debug("loop candidate {} for keyframe {}: {} matches, too few", candidate->id(), current->id(), n);
      continue;
    }
    const int pnp_inliers = match::poseFromMatchesByPnp(frame, matches, options.pnp);
    if (pnp_inliers == 0) {
      spdlog::debug("loop candidate {} for keyframe {}: {} matches, PnP failed", candidate->id(), current->id(), n);
      continue;
    }
    const int optimized = match::optimizeFramePoseDroppingOutliers(frame, options.pose);
    if (optimized < options.min_matches) {
      spdlog::debug("loop candidate {} for keyframe {}: {} matches, {} PnP inliers, {} after optimisation",
                    candidate->id(), current->id(), n, pnp_inliers, optimized);
      continue;
    }

    // The loop neighbourhood: the candidate and its covisible keyframes, projected with the verified pose.
    std::vector<map::KeyFramePtr> neighbourhood{candidate};
    for (const auto& [w, id] : candidate->orderedConnections()) {
      const map::KeyFramePtr kf = map.keyFrame(id);
      if (kf && !kf->isBad() && !connected.count(id)) neighbourhood.push_back(kf);
    }
    const int inliers = localizeAgainst(frame, neighbourhood, options);
    spdlog::debug("loop candidate {} for keyframe {}: {} matches, {} PnP inliers, {} inliers after projection "
                  "({} needed)",
                  candidate->id(), current->id(), n, pnp_inliers, inliers, needed);
    if (inliers < needed) continue;

    LoopCandidate loop;
    loop.current = current;
    loop.loop = candidate;
    loop.T_cw_corrected = frame.T_cw;
    loop.matches = frame.map_points;
    loop.inliers = inliers;
    loop.loop_keyframes = neighbourhood;
    std::unordered_set<const map::MapPoint*> seen;
    for (const auto& kf : neighbourhood) {
      for (const auto& p : kf->mapPoints()) {
        if (p && !p->isBad() && seen.insert(p.get()).second) loop.loop_points.push_back(p);
      }
    }
    return loop;
  }
  return std::nullopt;
}

}  // namespace amos::loop
