#include "amos/tracking/relocalizer.h"

#include <algorithm>

#include "amos/core/error.h"

namespace amos::tracking {

void RelocalizerOptions::check() const {
  core::require(num_candidates >= 1, "Relocalization.candidates must be >= 1");
  core::require(min_matches >= 6, "Relocalization.minMatches must be >= 6");
  core::require(match_ratio > 0 && match_ratio <= 1, "Relocalization.matchRatio must be in (0, 1]");
  core::require(min_inliers >= 10, "Relocalization.minInliers must be >= 10");
  pnp.check();
}

int optimizeFramePose(map::Frame& frame, const geometry::PoseOptimizerOptions& options) {
  std::vector<geometry::PoseObservation> obs;
  std::vector<int> index;
  const map::FrameFeatures& f = *frame.features;
  const std::vector<float>& inv_sigma2 = frame.sensor->invSigma2();
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto& p = frame.map_points[i];
    if (!p) continue;
    geometry::PoseObservation o;
    o.point_w = p->position();
    o.pixel = {f.keys[i].pt.x, f.keys[i].pt.y};
    o.u_right = f.u_right[i];
    o.inv_sigma2 = inv_sigma2[f.keys[i].octave];
    obs.push_back(o);
    index.push_back(static_cast<int>(i));
  }
  frame.outlier.assign(frame.size(), false);
  if (obs.size() < 3) return 0;
  const auto result = geometry::optimizePose(obs, frame.T_cw, frame.sensor->projection(), options);
  frame.setPose(result.T_cw);
  for (std::size_t k = 0; k < index.size(); ++k) frame.outlier[index[k]] = result.outlier[k];
  return result.num_inliers;
}

int poseFromMatchesByPnp(map::Frame& frame, const std::vector<map::MapPointPtr>& matches,
                         const geometry::PnpRansacOptions& options) {
  const map::FrameFeatures& f = *frame.features;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<int> index;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    if (!matches[i]) continue;
    points.push_back(matches[i]->position());
    pixels.emplace_back(f.keys[i].pt.x, f.keys[i].pt.y);
    index.push_back(static_cast<int>(i));
  }
  const geometry::PnpResult pnp = geometry::solvePnpRansac(points, pixels, frame.sensor->camera(), options);
  if (!pnp.success) return 0;
  frame.resetMatches();
  frame.setPose(pnp.T_cw);
  for (const int k : pnp.inliers) frame.map_points[index[k]] = matches[index[k]];
  return static_cast<int>(pnp.inliers.size());
}

Relocalizer::Relocalizer(const RelocalizerOptions& options, const MatchingOptions& matching,
                         const geometry::PoseOptimizerOptions& pose)
    : options_(options), matching_(matching), pose_(pose) {}

int optimizeFramePoseDroppingOutliers(map::Frame& frame, const geometry::PoseOptimizerOptions& options) {
  const int inliers = optimizeFramePose(frame, options);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.outlier[i]) {
      frame.map_points[i].reset();
      frame.outlier[i] = false;
    }
  }
  return inliers;
}

std::unordered_set<const map::MapPoint*> matchedPoints(const map::Frame& frame) {
  std::unordered_set<const map::MapPoint*> matched;
  for (const auto& p : frame.map_points) {
    if (p) matched.insert(p.get());
  }
  return matched;
}

int Relocalizer::optimize(map::Frame& frame) const { return optimizeFramePoseDroppingOutliers(frame, pose_); }

map::KeyFramePtr Relocalizer::relocalize(map::Frame& frame, const map::Map& map) const {
  // Rank keyframes by thumbnail distance (ties: older first, deterministic).
  std::vector<std::pair<double, map::KeyFramePtr>> ranked;
  for (const auto& kf : map.keyFrames()) {
    if (!kf->isBad()) ranked.emplace_back(map::thumbnailDistance(frame.thumbnail, kf->thumbnail()), kf);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (ranked.size() > static_cast<std::size_t>(options_.num_candidates)) ranked.resize(options_.num_candidates);

  for (const auto& [score, kf] : ranked) {
    int n = 0;
    std::vector<map::MapPointPtr> matches = matchFrameToKeyFrame(frame, *kf, options_.match_ratio, matching_, &n);
    if (n < options_.min_matches) continue;
    if (poseFromMatchesByPnp(frame, matches, options_.pnp) == 0) continue;
    int good = optimize(frame);
    if (good < 10) continue;
    if (good < options_.min_inliers) {
      // Look for more matches by projecting the keyframe's points with the estimated pose.
      const int extra = searchKeyFrameByProjection(frame, *kf, matchedPoints(frame), 10, 100, matching_);
      if (extra + good >= options_.min_inliers) {
        good = optimize(frame);
        if (good > 30 && good < options_.min_inliers) {
          const int more = searchKeyFrameByProjection(frame, *kf, matchedPoints(frame), 3, 64, matching_);
          if (good + more >= options_.min_inliers) good = optimize(frame);
        }
      }
    }
    if (good >= options_.min_inliers) return kf;
  }
  frame.resetMatches();
  return nullptr;
}

}  // namespace amos::tracking
