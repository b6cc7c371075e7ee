#include "amos/viewer/snapshot_publisher.h"

#include <shared_mutex>

#include <spdlog/spdlog.h>


#include "amos/core/error.h"
#include "amos/core/thread_priority.h"
#include "amos/core/thread_signals.h"
#include "amos/report/run_report.h"
#include "amos/viewer/delta_json.h"
#include "amos/viewer/dense_layer.h"
#include "amos/viewer/frame_image.h"
#include "amos/viewer/ground_truth_overlay.h"

namespace amos::viewer {
namespace {

TrajectoryPoint centreOf(double timestamp, const core::SE3& T_cw) {
  return {timestamp, T_cw.inverse().translation().cast<float>()};
}

nlohmann::json infoJson(const run::RunStart& s) {
  nlohmann::json map_source = nullptr;  // an empty map
  if (!s.loaded_map.empty()) {
    // What the run started from: the page shows it, so that the first map seen is known to be the loaded one.
    std::size_t keyframes = 0, points = 0;
    if (s.map) {
      std::shared_lock lock(s.map->mutex());
      keyframes = s.map->numKeyFrames(), points = s.map->numMapPoints();
    }
    map_source = {{"file", s.loaded_map}, {"localize", s.localize}, {"keyframes", keyframes}, {"points", points}};
  }
  return {{"sequence", s.sequence},
          {"mode", s.mode},
          {"loaded_map", map_source},
          {"frames", s.total_frames},
          {"live", true},
          {"has_ground_truth", !s.ground_truth.empty()},
          {"camera",
           {{"fx", s.camera.fx}, {"fy", s.camera.fy}, {"cx", s.camera.cx}, {"cy", s.camera.cy},
            {"width", s.camera.width}, {"height", s.camera.height}}}};
}

}  // namespace

SnapshotPublisher::SnapshotPublisher(LiveState& state, PublisherOptions options)
    : state_(state), options_(options) {}

SnapshotPublisher::~SnapshotPublisher() { stopThread(); }

void SnapshotPublisher::onStart(const run::RunStart& start) {
  {
    std::lock_guard lock(map_mutex_);
    map_ = start.map;
  }
  ground_truth_ = start.ground_truth;
  LiveUpdate u;
  u.info = infoJson(start);
  state_.apply(u);
  {
    std::lock_guard lock(mutex_);
    running_ = true;
  }
  thread_ = std::thread([this] { run(); });
}

void SnapshotPublisher::onFrame(const run::FrameSnapshot& frame) {
  {
    std::lock_guard lock(mutex_);
    if (latest_) ++dropped_;
    latest_ = frame;
    new_poses_.push_back(centreOf(frame.timestamp, frame.T_cw));
  }
  wake_.notify_one();
}

std::size_t SnapshotPublisher::droppedSnapshots() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

void SnapshotPublisher::run() {
  // The run's signals (SIGINT, SIGTERM) are for the main thread; background work runs after the frame's own.
  core::blockTerminationSignalsInThisThread();
  core::lowerThisThreadPriority(core::kBackgroundNice);
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [&] { return stop_ || latest_.has_value() || pending_dense_.has_value(); });
    if (stop_ && !latest_) break;  // stopped with no frame left (onEnd takes a waiting dense cloud)
    std::optional<run::FrameSnapshot> frame = std::move(latest_);
    latest_.reset();
    std::vector<TrajectoryPoint> poses = std::move(new_poses_);
    new_poses_.clear();
    const Clock::time_point now = Clock::now();
    std::optional<ColouredGeometry> dense;
    if (pending_dense_ && now - last_dense_time_ >= options_.dense_period) {
      dense = std::move(pending_dense_);
      pending_dense_.reset();
      last_dense_time_ = now;
    }
    const bool stopping = stop_;
    lock.unlock();
    if (frame) {
      const bool with_map = now - last_map_time_ >= options_.map_period;
      if (with_map) last_map_time_ = now;
      publishFrame(*frame, std::move(poses), with_map);
    }
    if (dense) publishDense(std::move(*dense));
    lock.lock();
    if (stopping) break;
    // The rate bound: the next publication waits for the period (or the end), whatever arrives meanwhile.
    wake_.wait_until(lock, now + options_.frame_period, [&] { return stop_; });
  }
}

void SnapshotPublisher::publishDenseCloud(std::vector<float> xyz, std::vector<std::uint8_t> rgb) {
  core::require(xyz.size() % 3 == 0 && rgb.size() == xyz.size(),
                "viewer: publishDenseCloud needs 3 coordinates and 3 colour bytes per point");
  ColouredGeometry cloud;
  cloud.xyz = std::move(xyz);
  cloud.rgb = std::move(rgb);
  {
    std::lock_guard lock(mutex_);
    if (running_) {
      pending_dense_ = std::move(cloud);
      wake_.notify_one();
      return;
    }
  }
  publishDense(std::move(cloud));
}

void SnapshotPublisher::publishDense(ColouredGeometry cloud) {
  state_.setDenseLayer("live", thinPoints(std::move(cloud), options_.dense_max_points));
}

MapDelta SnapshotPublisher::mapDelta() {
  MapSnapshot snapshot;
  {
    std::lock_guard lock(map_mutex_);
    if (map_ == nullptr) return {};
    snapshot = takeMapSnapshot(*map_);
  }
  MapDelta delta = diffMaps(last_map_, snapshot);
  last_map_ = std::move(snapshot);
  return delta;
}

void SnapshotPublisher::publishFrame(const run::FrameSnapshot& frame, std::vector<TrajectoryPoint> poses,
                                     bool with_map) {
  for (const TrajectoryPoint& p : poses) {
    io::StampedPose s;
    s.timestamp = p.timestamp;
    s.T_wc.translation() = p.position.cast<double>();
    estimate_.push_back(s);
  }
  LiveUpdate u;
  const double dt = frame.elapsed_s - last_elapsed_s_;
  const double fps = dt > 0 ? (frame.processed - last_processed_) / dt : 0.0;
  last_elapsed_s_ = frame.elapsed_s;
  last_processed_ = frame.processed;
  u.frame = frameStatusJson(frame, fps);
  u.trajectory = std::move(poses);
  if (with_map) u.map = mapDelta();
  const Clock::time_point now = Clock::now();
  if (!ground_truth_.empty() && now - last_alignment_time_ >= options_.ground_truth_period) {
    last_alignment_time_ = now;
    if (const auto alignment = alignEstimate(ground_truth_, estimate_))
      u.ground_truth = groundTruthInMapFrame(ground_truth_, *alignment);
  }
  if (!frame.bgr.empty()) {
    state_.setFrameImage(
        encodeJpeg(renderFrameOverlay(frame.bgr, frame.dynamic_mask, frame.keypoints, options_.image_width)));
    u.frame_image = true;
  }
  state_.apply(u);
}

void SnapshotPublisher::stopThread() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  std::optional<ColouredGeometry> dense;
  {
    std::lock_guard lock(mutex_);
    running_ = false;
    dense = std::move(pending_dense_);
    pending_dense_.reset();
  }
  // The newest cloud the thread had not published yet (its period had not passed).
  if (dense) publishDense(std::move(*dense));
}

void SnapshotPublisher::onEnd(const std::vector<io::StampedPose>& trajectory, const report::RunInfo& info) {
  stopThread();
  LiveUpdate u;
  u.map = mapDelta();
  {
    std::lock_guard lock(map_mutex_);
    map_ = nullptr;
  }
  u.trajectory_reset = true;
  for (const io::StampedPose& p : trajectory)
    u.trajectory.push_back({p.timestamp, p.T_wc.translation().cast<float>()});
  if (info.evaluation && !ground_truth_.empty())
    u.ground_truth = groundTruthInMapFrame(ground_truth_, info.evaluation->alignment);
  nlohmann::json summary = {{"end", report::toString(info.end.status)},
                            {"wall_time_s", info.wall_time_s},
                            {"frames", trajectory.size()}};
  if (info.evaluation) summary["evaluation"] = eval::toJson(*info.evaluation);
  u.summary = std::move(summary);
  state_.apply(u);
  spdlog::debug("viewer: {} snapshots replaced before they were published", droppedSnapshots());
}

}  // namespace amos::viewer
