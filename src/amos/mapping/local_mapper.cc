#include "amos/mapping/local_mapper.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <optional>
#include <shared_mutex>
#include <vector>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/core/stage_timer.h"
#include "amos/core/thread_priority.h"
#include "amos/mapping/local_bundle_adjustment.h"

namespace amos::mapping {

void LocalMappingOptions::check() const {
  core::requireOption(recent_found_ratio >= 0 && recent_found_ratio <= 1,
                      core::option(recent_found_ratio, "recent_found_ratio"),
                      fmt::format("must be in [0, 1], got {}", recent_found_ratio));
  core::requireAtLeast(recent_min_observations, "recent_min_observations", 0);
  core::requireOption(redundant_ratio > 0 && redundant_ratio <= 1, core::option(redundant_ratio, "redundant_ratio"),
                      fmt::format("must be in (0, 1], got {}", redundant_ratio));
  core::requireAtLeast(redundant_observers, "redundant_observers", 1);
  new_points.check();
  fusion.check();
  dynamic_culling.check();
  ba.check();
}

LocalMapper::LocalMapper(const LocalMappingOptions& options, std::shared_ptr<map::Map> map, bool lock_step,
                         core::StageTimes* times, KeyFrameHook after_keyframe)
    : options_(options),
      map_(std::move(map)),
      lock_step_(lock_step),
      times_(times),
      after_keyframe_(std::move(after_keyframe)) {
  options_.check();
  core::require(map_ != nullptr, "LocalMapper: map must not be null");
  thread_ = std::thread([this] { run(); });
}

LocalMapper::~LocalMapper() { stop(); }

void LocalMapper::insertKeyFrame(const map::KeyFramePtr& kf, std::vector<map::MapPointPtr> new_points) {
  {
    std::lock_guard lock(mutex_);
    if (failure_) std::rethrow_exception(failure_);
    core::require(!stopping_, "LocalMapper: keyframe inserted after stop()");
    queue_.push_back({kf, std::move(new_points)});
    abort_ba_.store(true);
  }
  work_cv_.notify_one();
  if (lock_step_) {
    waitUntilIdle();
    rethrowIfFailed();
  }
}

std::exception_ptr LocalMapper::failure() const {
  std::lock_guard lock(mutex_);
  return failure_;
}

void LocalMapper::rethrowIfFailed() const {
  if (const std::exception_ptr e = failure()) std::rethrow_exception(e);
}

bool LocalMapper::isIdle() const {
  std::lock_guard lock(mutex_);
  return queue_.empty() && !busy_;
}

std::size_t LocalMapper::queuedKeyFrames() const {
  std::lock_guard lock(mutex_);
  return queue_.size();
}

void LocalMapper::waitUntilIdle() {
  std::unique_lock lock(mutex_);
  idle_cv_.wait(lock, [&] { return queue_.empty() && !busy_; });
}

void LocalMapper::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  work_cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

LocalMappingStats LocalMapper::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void LocalMapper::run() {
  // Background work: keyframes queue, frames do not wait for it (core/thread_priority.h).
  core::lowerThisThreadPriority(core::kBackgroundNice);
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      work_cv_.wait(lock, [&] { return stopping_ || failure_ || !queue_.empty(); });
      if (failure_ || queue_.empty()) break;  // failed, or stopping and nothing left
      job = std::move(queue_.front());
      queue_.pop_front();
      busy_ = true;
      abort_ba_.store(!queue_.empty());
    }
    const map::KeyFrameId id = job.kf->id();
    std::exception_ptr failure;
    try {
      process(std::move(job));
    } catch (const std::exception& e) {
      failure =
          std::make_exception_ptr(core::Error(fmt::format("local mapping failed on keyframe {}: {}", id, e.what())));
    } catch (...) {
      failure = std::make_exception_ptr(core::Error(fmt::format("local mapping failed on keyframe {}", id)));
    }
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
      if (failure) {
        failure_ = failure;
        queue_.clear();  // the map is in no state to go on; the run ends at the next frame boundary
      }
    }
    idle_cv_.notify_all();
  }
  idle_cv_.notify_all();
}

void LocalMapper::process(Job job) {
  core::Stopwatch total, watch;
  const double cpu_start = core::threadCpuMs();
  const map::KeyFramePtr& kf = job.kf;
  LocalMappingStats delta;
  std::size_t job_new_points = 0;
  {
    std::unique_lock lock(map_->mutex());
    if (kf->isBad()) return;
    for (const auto& p : kf->mapPoints()) {
      if (!p || p->isBad()) continue;
      map_->updateNormalAndDepth(p);
      map_->updateDescriptor(p);
    }
    map_->updateConnections(kf);
    job_new_points = job.new_points.size();
    for (auto& p : job.new_points) recent_points_.push_back(std::move(p));
    const int before = static_cast<int>(map_->numMapPoints());
    cullRecentPoints(kf);
    delta.points_culled = before - static_cast<int>(map_->numMapPoints());
    delta.dynamic_points_culled = cullDynamicPoints(*map_, options_.dynamic_culling);
  }
  if (times_) times_->add("mapping.process_keyframe", watch.elapsedMs());
  watch.restart();
  std::vector<NewPointCandidate> candidates;
  {
    std::shared_lock lock(map_->mutex());
    candidates = findNewPoints(*map_, kf, options_.new_points);
  }
  {
    std::unique_lock lock(map_->mutex());
    auto added = addNewPoints(*map_, candidates, kf->frameId());
    delta.points_triangulated = static_cast<int>(added.size());
    for (auto& p : added) recent_points_.push_back(std::move(p));
  }
  if (times_) times_->add("mapping.new_points", watch.elapsedMs());
  watch.restart();
  if (queuedKeyFrames() == 0) {
    std::unique_lock lock(map_->mutex());
    delta.points_fused = match::fuseWithNeighbors(*map_, kf, options_.fusion);
    if (spdlog::should_log(spdlog::level::debug)) {  // the counts walk the keyframe's points: only when shown
      spdlog::debug("keyframe {}: {} new points, {} triangulated, {} fused; points {} seen by 2+ keyframes {} "
                    "neighbours {}",
                    kf->id(), job_new_points, delta.points_triangulated, delta.points_fused, kf->trackedMapPoints(0),
                    kf->trackedMapPoints(3), kf->orderedConnections().size());
    }
  }
  if (times_) times_->add("mapping.fusion", watch.elapsedMs());
  if (queuedKeyFrames() == 0) {
    watch.restart();
    if (options_.local_ba && map_->numKeyFrames() > 2) {
      const BaStats ba = runLocalBundleAdjustment(*map_, kf, options_.ba, &abort_ba_);
      spdlog::debug("local BA for keyframe {}: {} local + {} fixed keyframes, {} points, {} observations, {} outliers{}",
                    kf->id(), ba.adjusted_keyframes, ba.fixed_keyframes, ba.points, ba.observations,
                    ba.outliers_removed, ba.aborted ? " (aborted)" : "");
      ++delta.ba_runs;
      delta.ba_aborted += ba.aborted;
      if (times_) times_->add("mapping.local_ba", watch.elapsedMs());
    }
    watch.restart();
    if (options_.cull_keyframes) {
      std::unique_lock lock(map_->mutex());
      const auto before = map_->numKeyFrames();
      cullKeyFrames(kf);
      delta.keyframes_culled = static_cast<int>(before - map_->numKeyFrames());
    }
    if (times_) times_->add("mapping.cull_keyframes", watch.elapsedMs());
  }
  if (after_keyframe_) {
    watch.restart();
    after_keyframe_(kf);
    if (times_) times_->add("mapping.after_keyframe", watch.elapsedMs());
  }
  if (times_) times_->add("mapping.keyframe_total", total.elapsedMs());
  // CPU of the mapping thread on this keyframe, loop closing's hook included (the wall times above grow with load).
  if (times_) times_->add("cpu.mapping", core::threadCpuMs() - cpu_start);
  std::lock_guard lock(mutex_);
  ++stats_.keyframes_processed;
  stats_.keyframes_culled += delta.keyframes_culled;
  stats_.points_triangulated += delta.points_triangulated;
  stats_.points_culled += delta.points_culled;
  stats_.points_fused += delta.points_fused;
  stats_.ba_runs += delta.ba_runs;
  stats_.ba_aborted += delta.ba_aborted;
  stats_.dynamic_points_culled += delta.dynamic_points_culled;
}

void LocalMapper::cullRecentPoints(const map::KeyFramePtr& kf) {
  const map::KeyFrameId current = kf->id();
  for (auto it = recent_points_.begin(); it != recent_points_.end();) {
    const map::MapPointPtr& p = *it;
    const map::KeyFrameId age = current >= p->firstKeyFrame() ? current - p->firstKeyFrame() : 0;
    if (p->isBad()) {
      it = recent_points_.erase(it);
    } else if (p->foundRatio() < options_.recent_found_ratio) {
      map_->setMapPointBad(p);
      it = recent_points_.erase(it);
    } else if (age >= 2 && p->numObservations() <= options_.recent_min_observations) {
      map_->setMapPointBad(p);
      it = recent_points_.erase(it);
    } else if (age >= 3) {
      it = recent_points_.erase(it);  // survived its probation
    } else {
      ++it;
    }
  }
}

void LocalMapper::cullKeyFrames(const map::KeyFramePtr& current) {
  const double close = current->sensor().closeDepth();
  const auto neighbours = current->orderedConnections();
  // The observers' keyframes by id, each looked up in the map once per call instead of once per observation (an
  // ordered-map search and a shared_ptr copy, tens of thousands per keyframe). A keyframe culled below has its
  // observations erased from its points, so no later lookup asks for it.
  std::vector<std::optional<map::KeyFramePtr>> observers_by_id;  // nullopt: not looked up yet
  auto observer = [&](map::KeyFrameId other) -> const map::KeyFramePtr& {
    if (other >= observers_by_id.size())
      observers_by_id.resize(std::max<std::size_t>(other + 1, map_->nextKeyFrameId()));
    std::optional<map::KeyFramePtr>& kf = observers_by_id[other];
    if (!kf) kf = map_->keyFrame(other);
    return *kf;
  };
  for (const auto& [w, id] : neighbours) {
    if (id == map_->firstKeyFrameId()) continue;
    const map::KeyFramePtr kf = map_->keyFrame(id);
    if (!kf || kf->isBad()) continue;
    const map::FrameFeatures& f = kf->features();
    int redundant = 0, considered = 0;
    for (int i = 0; i < kf->size(); ++i) {
      const map::MapPointPtr& p = kf->mapPoint(i);
      if (!p || p->isBad()) continue;
      if (f.depth[i] > close || f.depth[i] < 0) continue;  // RGB-D: judge on close points only
      ++considered;
      if (p->numObservations() <= options_.redundant_observers) continue;
      const int level = f.keys[i].octave;
      int observers = 0;
      for (const auto& [other, idx] : p->observations()) {
        if (other == id) continue;
        const map::KeyFramePtr& o = observer(other);
        if (!o) continue;
        if (o->features().keys[idx].octave <= level + 1 && ++observers >= options_.redundant_observers) break;
      }
      if (observers >= options_.redundant_observers) ++redundant;
    }
    if (redundant > options_.redundant_ratio * considered) map_->setKeyFrameBad(kf);
  }
}

}  // namespace amos::mapping
