#include "amos/viewer/culled_recorder.h"



#include "amos/core/thread_priority.h"
#include "amos/core/thread_signals.h"

namespace amos::viewer {

CulledPointRecorder::CulledPointRecorder(std::chrono::milliseconds period, std::size_t max_points)
    : period_(period), max_points_(max_points) {}

CulledPointRecorder::~CulledPointRecorder() { finish(); }

void CulledPointRecorder::start(std::shared_ptr<const map::Map> map) {
  if (map == nullptr || thread_.joinable()) return;
  map_ = std::move(map);
  look();  // the map the run starts from (empty, or a loaded one): its later removals count
  thread_ = std::thread([this] { run(); });
}

void CulledPointRecorder::run() {
  // The run's signals are for the main thread; this is background work.
  core::blockTerminationSignalsInThisThread();
  core::lowerThisThreadPriority(core::kBackgroundNice);
  std::unique_lock lock(mutex_);
  while (!stop_) {
    // The next look after the period, or at once when finish asks to stop.
    if (wake_.wait_for(lock, period_, [&] { return stop_; })) break;
    lock.unlock();
    look();
    lock.lock();
  }
}

void CulledPointRecorder::look() {
  MapSnapshot now = takeMapSnapshot(*map_);
  const MapDelta delta = diffMaps(last_, now);
  for (const PointSample& p : delta.culled)
    if (culled_.size() < max_points_) culled_.push_back(p);
  last_ = std::move(now);
}

std::vector<PointSample> CulledPointRecorder::finish() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  if (!thread_.joinable()) return culled_;
  thread_.join();
  look();  // what was culled since the thread's last look
  map_ = nullptr;
  return culled_;
}

}  // namespace amos::viewer
