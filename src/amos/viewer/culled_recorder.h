#pragma once
// The map points removed as dynamic over a whole run (the red points of the live page), recorded for
// report.html so that `amos-slam view` of the finished run shows them too. Its own thread looks at the map every
// `period` (a map snapshot under a brief shared lock, map_delta.h) and keeps the removed points that meet the
// dynamic culling rule (diffMaps' `culled`), at most `max_points`. The run's thread never waits for it: start
// and finish are called from the run's observer hooks (onStart, onEnd), nothing per frame.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "amos/map/map.h"
#include "amos/viewer/map_delta.h"

namespace amos::viewer {

class CulledPointRecorder {
 public:
  explicit CulledPointRecorder(std::chrono::milliseconds period = std::chrono::milliseconds(1000),
                               std::size_t max_points = 100000);
  ~CulledPointRecorder();
  CulledPointRecorder(const CulledPointRecorder&) = delete;
  CulledPointRecorder& operator=(const CulledPointRecorder&) = delete;

  // Takes a first look at `map` and starts the thread (null: nothing to record).
  void start(std::shared_ptr<const map::Map> map);
  // Stops the thread, takes a last look and releases the map; returns every culled point seen since start.
  std::vector<PointSample> finish();

 private:
  void run();
  void look();  // one snapshot and its difference to the previous one

  std::chrono::milliseconds period_;
  std::size_t max_points_;
  std::mutex mutex_;  // guards stop_
  std::condition_variable wake_;
  bool stop_ = false;
  // Used by the thread only (and by finish after it ended).
  std::shared_ptr<const map::Map> map_;
  MapSnapshot last_;
  std::vector<PointSample> culled_;
  std::thread thread_;
};

}  // namespace amos::viewer
