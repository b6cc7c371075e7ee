#include "amos/tracking/relocalizer.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/match/brute_force_search.h"
#include "amos/match/pose_from_matches.h"
#include "amos/match/projection_search.h"
#include "amos/map/place_candidates.h"

namespace amos::tracking {

void RelocalizerOptions::check() const {
  core::requireAtLeast(num_candidates, "num_candidates", 1);
  core::requireAtLeast(min_matches, "min_matches", 6);
  core::requireOption(match_ratio > 0 && match_ratio <= 1, core::option(match_ratio, "match_ratio"),
                      fmt::format("must be in (0, 1], got {}", match_ratio));
  core::requireAtLeast(min_inliers, "min_inliers", 10);
  pnp.check();
}

Relocalizer::Relocalizer(const RelocalizerOptions& options, const match::MatchingOptions& matching,
                         const geometry::PoseOptimizerOptions& pose,
                         std::shared_ptr<const place::KeyFrameDatabase> places)
    : options_(options), matching_(matching), pose_(pose), places_(std::move(places)) {}

int Relocalizer::optimize(map::Frame& frame) const { return match::optimizeFramePoseDroppingOutliers(frame, pose_); }

std::vector<map::KeyFramePtr> Relocalizer::candidates(const map::Frame& frame, const map::Map& map) const {
  std::vector<map::KeyFramePtr> out;
  if (places_) {
    map::PlaceQueryOptions query;
    query.max_candidates = static_cast<std::size_t>(options_.num_candidates);
    for (const auto& [score, kf] :
         map::placeCandidates(map, *places_, places_->transform(frame.features->descriptors), query)) {
      out.push_back(kf);
    }
    return out;
  }
  // Rank keyframes by thumbnail distance (ties: older first, deterministic).
  std::vector<std::pair<double, map::KeyFramePtr>> ranked;
  for (const auto& kf : map.keyFrames()) {
    if (!kf->isBad()) ranked.emplace_back(map::thumbnailDistance(frame.thumbnail, kf->thumbnail()), kf);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (ranked.size() > static_cast<std::size_t>(options_.num_candidates)) ranked.resize(options_.num_candidates);
  for (auto& entry : ranked) out.push_back(std::move(entry.second));
  return out;
}

map::KeyFramePtr Relocalizer::relocalize(map::Frame& frame, const map::Map& map) const {
  for (const map::KeyFramePtr& kf : candidates(frame, map)) {
    int n = 0;
    std::vector<map::MapPointPtr> matches =
        match::matchFrameToKeyFrame(frame, *kf, options_.match_ratio, matching_, &n);
    // Why a candidate failed, for a relocalisation that comes late (-v): too few descriptor matches, no PnP pose,
    // or too few inliers after the projection searches.
    if (n < options_.min_matches) {
      spdlog::debug("frame {}: relocalisation candidate keyframe {}: {} matches (< {})", frame.id, kf->id(), n,
                    options_.min_matches);
      continue;
    }
    if (match::poseFromMatchesByPnp(frame, matches, options_.pnp) == 0) {
      spdlog::debug("frame {}: relocalisation candidate keyframe {}: {} matches, no PnP pose", frame.id, kf->id(), n);
      continue;
    }
    int good = optimize(frame);
    if (good < 10) {
      spdlog::debug("frame {}: relocalisation candidate keyframe {}: {} matches, {} inliers", frame.id, kf->id(), n,
                    good);
      continue;
    }
    if (good < options_.min_inliers) {
      // Look for more matches by projecting the keyframe's points with the estimated pose.
      const int extra = match::searchKeyFrameByProjection(frame, *kf, match::matchedPoints(frame), 10, 100, matching_);
      if (extra + good >= options_.min_inliers) {
        good = optimize(frame);
        if (good > 30 && good < options_.min_inliers) {
          const int more = match::searchKeyFrameByProjection(frame, *kf, match::matchedPoints(frame), 3, 64, matching_);
          if (good + more >= options_.min_inliers) good = optimize(frame);
        }
      }
    }
    if (good >= options_.min_inliers) return kf;
    spdlog::debug("frame {}: relocalisation candidate keyframe {}: {} matches, {} inliers (< {})", frame.id, kf->id(),
                  n, good, options_.min_inliers);
  }
  frame.resetMatches();
  return nullptr;
}

}  // namespace amos::tracking
