#include "amos/mapping/local_bundle_adjustment.h"

#include <mutex>
#include <shared_mutex>
#include <unordered_map>

namespace amos::mapping {

namespace {

// Bundle adjustment of the keyframes `select` picks (called under the map's shared lock; empty = nothing to do)
// and every point they see; the other keyframes that see those points are held fixed, as is the map's first.
template <typename Select>
BaStats runBundleAdjustment(map::Map& map, Select select, const BundleAdjustmentOptions& options,
                                 const std::atomic<bool>* abort) {
  BaStats stats;
  BaProblem problem;
  std::vector<map::KeyFramePtr> kfs;
  std::vector<map::MapPointPtr> pts;
  struct ObsRef {
    map::MapPointPtr point;
    map::KeyFramePtr kf;
  };
  std::vector<ObsRef> obs_refs;
  {
    std::shared_lock lock(map.mutex());
    const std::vector<map::KeyFramePtr> local = select();
    if (local.empty()) return stats;
    problem.projection = local.front()->sensor().projection();
    std::unordered_map<map::KeyFrameId, int> kf_index;
    auto addKf = [&](const map::KeyFramePtr& kf, bool fixed) {
      kf_index[kf->id()] = static_cast<int>(kfs.size());
      kfs.push_back(kf);
      problem.keyframes.push_back({kf->T_cw(), fixed || kf->id() == map.firstKeyFrameId()});
    };
    for (const auto& kf : local) addKf(kf, false);
    stats.adjusted_keyframes = static_cast<int>(kfs.size());
    // Local points, in keyframe then keypoint order (deterministic).
    std::unordered_map<const map::MapPoint*, int> pt_index;
    for (int k = 0; k < stats.adjusted_keyframes; ++k) {
      for (const auto& p : kfs[k]->mapPoints()) {
        if (!p || p->isBad() || pt_index.count(p.get())) continue;
        pt_index[p.get()] = static_cast<int>(pts.size());
        pts.push_back(p);
        problem.points.push_back({p->position()});
      }
    }
    // Fixed keyframes: observers of local points outside the local set.
    for (const auto& p : pts) {
      for (const auto& [id, idx] : p->observations()) {
        if (kf_index.count(id)) continue;
        const map::KeyFramePtr kf = map.keyFrame(id);
        if (kf && !kf->isBad()) addKf(kf, true);
      }
    }
    stats.fixed_keyframes = static_cast<int>(kfs.size()) - stats.adjusted_keyframes;
    for (std::size_t k = 0; k < kfs.size(); ++k) {
      const std::optional<map::PoseLink>& link = kfs[k]->photometricLink();
      if (!link) continue;
      const auto other = kf_index.find(link->reference);
      if (other == kf_index.end()) continue;
      problem.relative_poses.push_back({static_cast<int>(k), other->second, link->T_kr, link->information});
    }
    const auto& inv_sigma2 = local.front()->sensor().invSigma2();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      for (const auto& [id, idx] : pts[i]->observations()) {
        const auto it = kf_index.find(id);
        if (it == kf_index.end()) continue;
        const map::KeyFrame& kf = *kfs[it->second];
        const cv::KeyPoint& kp = kf.features().keys[idx];
        BaObservation o;
        o.keyframe = it->second;
        o.point = static_cast<int>(i);
        o.pixel = {kp.pt.x, kp.pt.y};
        o.u_right = kf.features().u_right[idx];
        o.inv_sigma2 = inv_sigma2[kp.octave];
        problem.observations.push_back(o);
        obs_refs.push_back({pts[i], kfs[it->second]});
      }
    }
  }
  stats.points = static_cast<int>(pts.size());
  stats.observations = static_cast<int>(problem.observations.size());
  if (problem.observations.empty()) return stats;

  const BaResult result = solveBundleAdjustment(problem, options, abort);
  stats.aborted = result.aborted;

  std::unique_lock lock(map.mutex());
  for (std::size_t j = 0; j < result.outlier.size(); ++j) {
    if (!result.outlier[j]) continue;
    const ObsRef& r = obs_refs[j];
    if (r.point->isBad() || r.kf->isBad() || !r.point->isObservedBy(r.kf->id())) continue;
    map.eraseObservation(r.point, r.kf->id());
    ++stats.outliers_removed;
  }
  for (int k = 0; k < stats.adjusted_keyframes; ++k) {
    if (!kfs[k]->isBad() && !problem.keyframes[k].fixed) kfs[k]->setPose(result.T_cw[k]);
  }
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (pts[i]->isBad()) continue;
    pts[i]->setPosition(result.positions[i]);
    map.updateNormalAndDepth(pts[i]);
  }
  return stats;
}

}  // namespace

BaStats runLocalBundleAdjustment(map::Map& map, const map::KeyFramePtr& keyframe,
                                      const BundleAdjustmentOptions& options, const std::atomic<bool>* abort) {
  auto select = [&] {
    std::vector<map::KeyFramePtr> local;
    if (keyframe->isBad()) return local;
    local.push_back(keyframe);
    for (const auto& [w, id] : keyframe->orderedConnections()) {  // most covisible first
      if (options.max_keyframes > 0 && static_cast<int>(local.size()) > options.max_keyframes) break;
      const map::KeyFramePtr kf = map.keyFrame(id);
      if (kf && !kf->isBad()) local.push_back(kf);
    }
    return local;
  };
  return runBundleAdjustment(map, select, options, abort);
}

BaStats runGlobalBundleAdjustment(map::Map& map, const BundleAdjustmentOptions& options,
                                       const std::atomic<bool>* abort) {
  auto select = [&] {
    std::vector<map::KeyFramePtr> all;
    for (const auto& kf : map.keyFrames())
      if (!kf->isBad()) all.push_back(kf);
    return all;
  };
  return runBundleAdjustment(map, select, options, abort);
}

}  // namespace amos::mapping
