#pragma once
// The local-mapping thread (ORB-SLAM2's LocalMapping): for each keyframe handed over by tracking it completes the
// point bookkeeping and covisibility links, culls recently created points that tracking does not confirm,
// triangulates new points with its neighbours, fuses duplicates, runs local bundle adjustment and removes
// redundant keyframes.
//
// Threads: keyframes arrive through insertKeyFrame() (tracking thread) and are processed in the mapper's own
// thread, woken by a condition variable. Tracking never waits for bundle adjustment: a new keyframe raises the
// abort flag, which the solver checks every iteration. In lock-step mode (deterministic runs) insertKeyFrame()
// returns only once the keyframe is fully processed, so the map evolves identically on every run.
//
// Failures: an exception while processing a keyframe (the after-keyframe hook, i.e. loop closing, included) stops
// the mapping: the keyframes still queued are dropped, and the failure (a core::Error naming the keyframe and the
// cause) is handed over under the mutex to the tracking thread, which gets it from the next insertKeyFrame() or
// rethrowIfFailed() (SlamSystem calls it at every frame boundary). Nothing is logged and forgotten.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <thread>

#include "amos/core/stage_timer.h"
#include "amos/map/map.h"
#include "amos/mapping/bundle_adjustment.h"
#include "amos/mapping/dynamic_culling.h"
#include "amos/mapping/new_points.h"
#include "amos/match/fuse.h"
#include "amos/tracking/keyframe_sink.h"

namespace amos::mapping {

struct LocalMappingOptions {
  double recent_found_ratio = 0.25;  // Mapping.recentFoundRatio: cull a new point found in fewer of the frames that should see it
  int recent_min_observations = 3;   // Mapping.recentMinObservations: ... or with fewer observations 2 keyframes later
  double redundant_ratio = 0.9;      // Mapping.redundantRatio: a keyframe whose close points are this often seen ...
  int redundant_observers = 3;       // Mapping.redundantObservers: ... by this many other keyframes is culled
  bool local_ba = true;              // LocalBA.enabled
  bool cull_keyframes = true;        // Mapping.cullKeyFrames
  NewPointsOptions new_points;
  match::FusionOptions fusion;
  DynamicCullingOptions dynamic_culling;
  BundleAdjustmentOptions ba;
  void check() const;
};

struct LocalMappingStats {
  int keyframes_processed = 0, keyframes_culled = 0;
  int points_triangulated = 0, points_culled = 0, points_fused = 0;
  int ba_runs = 0, ba_aborted = 0;
  int dynamic_points_culled = 0;
};

// Called in the mapping thread after each keyframe is processed, without any lock held (loop closing hooks in
// here, so it runs with local mapping paused).
using KeyFrameHook = std::function<void(const map::KeyFramePtr&)>;

class LocalMapper final : public tracking::KeyFrameSink {
 public:
  // lock_step: insertKeyFrame() waits until the keyframe is processed (deterministic mode).
  LocalMapper(const LocalMappingOptions& options, std::shared_ptr<map::Map> map, bool lock_step,
              core::StageTimes* times = nullptr, KeyFrameHook after_keyframe = {});
  ~LocalMapper() override;
  LocalMapper(const LocalMapper&) = delete;
  LocalMapper& operator=(const LocalMapper&) = delete;

  void insertKeyFrame(const map::KeyFramePtr& kf, std::vector<map::MapPointPtr> new_points) override;
  bool isIdle() const override;
  std::size_t queuedKeyFrames() const override;
  void interruptBundleAdjustment() override { abort_ba_.store(true); }

  // Blocks until every queued keyframe is processed.
  void waitUntilIdle();
  // Processes what is queued, then stops the thread (idempotent; also done by the destructor). Never throws: a
  // failure while processing is kept for failure() / rethrowIfFailed().
  void stop();
  // The failure that stopped the mapping, or null.
  std::exception_ptr failure() const;
  void rethrowIfFailed() const;
  LocalMappingStats stats() const;

 private:
  struct Job {
    map::KeyFramePtr kf;
    std::vector<map::MapPointPtr> new_points;
  };
  void run();
  void process(Job job);
  void cullRecentPoints(const map::KeyFramePtr& kf);
  void cullKeyFrames(const map::KeyFramePtr& kf);

  LocalMappingOptions options_;
  std::shared_ptr<map::Map> map_;
  const bool lock_step_;
  core::StageTimes* times_;
  KeyFrameHook after_keyframe_;

  mutable std::mutex mutex_;
  std::condition_variable work_cv_, idle_cv_;
  std::deque<Job> queue_;
  bool busy_ = false, stopping_ = false;
  std::exception_ptr failure_;                 // guarded by mutex_: set once, by the mapper thread
  std::atomic<bool> abort_ba_{false};
  std::list<map::MapPointPtr> recent_points_;  // mapper thread only
  LocalMappingStats stats_;                    // guarded by mutex_
  std::thread thread_;
};

}  // namespace amos::mapping
