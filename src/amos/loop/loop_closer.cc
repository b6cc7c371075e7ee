#include "amos/loop/loop_closer.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <map>
#include <mutex>
#include <set>
#include <shared_mutex>
#include <unordered_map>
#include <unordered_set>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/core/stage_timer.h"

namespace amos::loop {

void LoopClosingOptions::check() const {
  core::requireOption(essential_min_weight >= 1, core::option(essential_min_weight, "essential_min_weight"),
                      fmt::format("must be >= 1, got {}", essential_min_weight));
  detector.check();
  pose_graph.check();
  fusion.check();
}

LoopCloser::LoopCloser(const LoopClosingOptions& options, std::shared_ptr<map::Map> map,
                       std::shared_ptr<const place::KeyFrameDatabase> places)
    : options_(options), map_(std::move(map)), places_(std::move(places)), consistency_(options.detector.consistency) {
  options_.check();
  core::require(map_ != nullptr, "LoopCloser: map must not be null");
}

std::optional<LoopClosureReport> LoopCloser::process(const map::KeyFramePtr& kf) {
  if (!options_.enabled) return std::nullopt;
  std::optional<LoopCandidate> loop;
  {
    std::shared_lock lock(map_->mutex());
    loop = detectLoop(*map_, kf, last_loop_kf_, options_.detector, &consistency_, places_.get());
  }
  if (!loop) return std::nullopt;
  LoopClosureReport report;
  report.current = kf->id();
  report.loop = loop->loop->id();
  report.inliers = loop->inliers;
  {
    std::unique_lock lock(map_->mutex());
    if (kf->isBad() || loop->loop->isBad()) return std::nullopt;
    correct(*loop, report);
  }
  last_loop_kf_ = kf->id();
  consistency_.reset();
  {
    std::lock_guard guard(closures_mutex_);
    closures_.push_back(report);
  }
  spdlog::info("loop closed: keyframe {} -> {} ({} inliers, moved {:.3f} m / {:.2f} deg, {} points fused)",
               report.current, report.loop, report.inliers, report.correction_m, report.correction_deg,
               report.fused);
  return report;
}

std::vector<LoopClosureReport> LoopCloser::closures() const {
  std::lock_guard guard(closures_mutex_);
  return closures_;
}

void LoopCloser::correct(const LoopCandidate& loop, LoopClosureReport& report) {
  map::Map& map = *map_;
  const map::KeyFramePtr& current = loop.current;
  const std::vector<map::KeyFramePtr> keyframes = map.keyFrames();
  std::unordered_map<map::KeyFrameId, core::SE3> before;  // poses before any correction
  for (const auto& kf : keyframes) before[kf->id()] = kf->T_cw();

  // 2. The current neighbourhood moves rigidly with the current keyframe.
  const core::SE3 T_wc_old = current->T_wc();
  std::vector<map::KeyFramePtr> neighbourhood{current};
  for (const auto& [w, id] : current->orderedConnections()) {
    const map::KeyFramePtr kf = map.keyFrame(id);
    if (kf && !kf->isBad()) neighbourhood.push_back(kf);
  }
  // Each neighbour is first moved rigidly with the current keyframe, then localised against the loop side
  // itself: drift inside the neighbourhood would otherwise end up in the loop links.
  std::unordered_map<map::KeyFrameId, core::SE3> corrected;  // initial values of the pose graph
  std::unordered_set<map::KeyFrameId> measured{current->id()};  // keyframes with a verified loop-side pose
  corrected[current->id()] = loop.T_cw_corrected;
  for (const auto& kf : neighbourhood) {
    if (kf == current) continue;
    map::Frame frame = frameOf(*kf);
    frame.setPose(kf->T_cw() * T_wc_old * loop.T_cw_corrected);
    corrected[kf->id()] = frame.T_cw;
    if (localizeAgainst(frame, loop.loop_keyframes, options_.detector) >= options_.detector.min_matches) {
      corrected[kf->id()] = frame.T_cw;
      measured.insert(kf->id());
    }
  }
  // Which keyframe moved a point: the pose graph later moves it on with that keyframe (ORB-SLAM2's
  // mnCorrectedReference), so a point never gets two different corrections.
  std::unordered_map<const map::MapPoint*, map::KeyFrameId> moved_by;
  for (const auto& kf : neighbourhood) {
    const core::SE3 T_new_old = corrected[kf->id()].inverse() * before[kf->id()];  // old world -> new world
    for (const auto& p : kf->mapPoints()) {
      if (!p || p->isBad() || !moved_by.emplace(p.get(), kf->id()).second) continue;
      p->setPosition(T_new_old * p->position());
    }
  }
  for (const auto& kf : neighbourhood) kf->setPose(corrected[kf->id()]);
  report.correction_m = core::translationNorm(loop.T_cw_corrected * T_wc_old);
  report.correction_deg = core::rotationAngle(loop.T_cw_corrected * T_wc_old) * 180.0 / M_PI;

  // 3. Fuse the loop side into the neighbourhood: first the verified matches of the current keyframe ...
  std::set<map::KeyFrameId> connected_before;
  for (const auto& kf : neighbourhood) {
    for (const auto& [w, id] : kf->orderedConnections()) connected_before.insert(id);
  }
  for (std::size_t i = 0; i < loop.matches.size(); ++i) {
    const map::MapPointPtr& loop_point = loop.matches[i];
    if (!loop_point || loop_point->isBad()) continue;
    const map::MapPointPtr own = current->mapPoint(static_cast<int>(i));
    if (own == loop_point) continue;
    if (own && !own->isBad()) {
      map.replaceMapPoint(own, loop_point);
    } else if (!loop_point->isObservedBy(current->id())) {
      map.addObservation(loop_point, current, static_cast<int>(i));
    }
    ++report.fused;
  }
  // ... then every loop point projected into every neighbourhood keyframe.
  for (const auto& kf : neighbourhood) {
    if (!kf->isBad()) report.fused += match::fusePoints(map, kf, loop.loop_points, options_.fusion);
  }
  for (const auto& kf : neighbourhood) {
    if (kf->isBad()) continue;
    for (const auto& p : kf->mapPoints()) {
      if (p && !p->isBad()) {
        map.updateDescriptor(p);
        map.updateNormalAndDepth(p);
      }
    }
    map.updateConnections(kf);
  }
  // The loop links: new links of the keyframes whose loop-side pose was measured.
  std::unordered_set<map::KeyFrameId> in_neighbourhood;
  for (const auto& kf : neighbourhood) in_neighbourhood.insert(kf->id());
  for (const auto& kf : neighbourhood) {
    if (kf->isBad() || !measured.count(kf->id())) continue;
    for (const auto& [w, id] : kf->orderedConnections()) {
      if (!in_neighbourhood.count(id) && !connected_before.count(id)) loop_edges_.emplace_back(kf->id(), id);
    }
  }
  loop_edges_.emplace_back(current->id(), loop.loop->id());

  // 4. Essential graph over all good keyframes.
  core::Stopwatch watch;
  std::vector<map::KeyFramePtr> vertices;
  std::unordered_map<map::KeyFrameId, int> index;
  for (const auto& kf : map.keyFrames()) {
    if (kf->isBad()) continue;
    index[kf->id()] = static_cast<int>(vertices.size());
    vertices.push_back(kf);
  }
  std::vector<core::SE3> initial;
  std::vector<bool> fixed;
  for (const auto& kf : vertices) {
    initial.push_back(kf->T_cw());
    fixed.push_back(kf->id() == map.firstKeyFrameId() || kf->id() == loop.loop->id());
  }
  // Odometry-like edges keep the relative poses from before the correction; loop edges those after it.
  // Rotation residuals in metres at the scene's median depth (see PoseGraphEdge::rotation_scale).
  const double depth = current->medianSceneDepth();
  const double rotation_scale = depth > 0 ? depth : 1.0;
  auto beforePose = [&](map::KeyFrameId id) { return before.count(id) ? before.at(id) : map.keyFramePose(id); };
  std::vector<PoseGraphEdge> edges;
  std::set<std::pair<int, int>> used;
  auto addEdge = [&](map::KeyFrameId a, map::KeyFrameId b, bool is_loop) {
    const auto ia = index.find(a), ib = index.find(b);
    if (ia == index.end() || ib == index.end() || a == b) return;
    const std::pair<int, int> key = std::minmax(ia->second, ib->second);
    if (!used.insert(key).second) return;
    const core::SE3 T_ab = is_loop ? vertices[ia->second]->T_cw() * vertices[ib->second]->T_cw().inverse()
                                   : beforePose(a) * beforePose(b).inverse();
    edges.push_back({ia->second, ib->second, T_ab, 1.0, rotation_scale});
  };
  for (const auto& [a, b] : loop_edges_) addEdge(a, b, true);
  for (const auto& kf : vertices) {
    if (kf->parent() != map::kNoKeyFrame) addEdge(kf->id(), kf->parent(), false);
    for (const map::KeyFrameId id : kf->covisiblesWithWeight(options_.essential_min_weight)) {
      addEdge(kf->id(), id, false);
    }
  }
  const PoseGraphResult solved = optimizePoseGraph(initial, fixed, edges, options_.pose_graph);
  report.pose_graph_ms = watch.elapsedMs();
  report.pose_graph_edges = static_cast<int>(edges.size());
  report.loop_edges = static_cast<int>(loop_edges_.size());
  report.pose_graph_iterations = solved.iterations;
  report.pose_graph_initial_cost = solved.initial_cost;
  report.pose_graph_final_cost = solved.final_cost;
  spdlog::debug("pose graph: {} keyframes, {} edges ({} loop), cost {:.3g} -> {:.3g} in {} iterations, {:.1f} ms",
                vertices.size(), edges.size(), loop_edges_.size(), solved.initial_cost, solved.final_cost,
                solved.iterations, report.pose_graph_ms);

  // Points follow their reference keyframe (the one that created them, or another observer if it is gone).
  std::unordered_map<map::KeyFrameId, core::SE3> delta;  // new world <- world before the pose graph
  for (std::size_t k = 0; k < vertices.size(); ++k) delta[vertices[k]->id()] = solved.T_iw[k].inverse() * initial[k];
  for (const auto& p : map.mapPoints()) {
    if (p->isBad()) continue;
    const auto mover = moved_by.find(p.get());
    auto it = delta.find(mover != moved_by.end() ? mover->second : p->referenceKeyFrame());
    if (it == delta.end()) {
      for (const auto& [id, idx] : p->observations()) {
        it = delta.find(id);
        if (it != delta.end()) break;
      }
    }
    if (it == delta.end()) continue;
    p->setPosition(it->second * p->position());
    map.updateNormalAndDepth(p);
  }
  for (std::size_t k = 0; k < vertices.size(); ++k) vertices[k]->setPose(solved.T_iw[k]);
}

}  // namespace amos::loop
