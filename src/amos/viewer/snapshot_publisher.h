#pragma once
// The live viewer's side of a run: a run::RunObserver that turns the run's per-frame snapshots into updates of
// a LiveState, in its own thread, at a bounded rate.
//
// onFrame (the run's thread) only stores the snapshot as the newest one, replacing a waiting older one (counted
// as dropped), appends the pose to the trajectory and wakes the thread: a constant, tiny cost whatever the
// browsers do. The thread publishes at most every `frame_period` (frame status, trajectory, the frame image) and
// takes a map snapshot at most every `map_period`, sending only what changed (map_delta.h), and the newest dense
// cloud handed to publishDenseCloud at most every `dense_period`. It never waits for a browser: LiveState keeps
// the events for the server's threads.
#include <chrono>
#include <cstdint>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "amos/run/run_observer.h"
#include "amos/viewer/live_state.h"
#include "amos/viewer/map_delta.h"
#include "amos/viewer/ply_file.h"

namespace amos::viewer {

struct PublisherOptions {
  std::chrono::milliseconds frame_period{200};   // frame status and image: at most 5 per second
  std::chrono::milliseconds map_period{500};     // map snapshots: at most 2 per second
  std::chrono::milliseconds ground_truth_period{3000};  // re-alignment of the ground truth to the estimate
  int image_width = 640;
  std::chrono::milliseconds dense_period{1000};  // the live dense cloud: at most 1 per second
  std::size_t dense_max_points = 400000;         // ... thinned to this many points (dense_layer.h: thinPoints)
};

class SnapshotPublisher : public run::RunObserver {
 public:
  explicit SnapshotPublisher(LiveState& state, PublisherOptions options = {});
  ~SnapshotPublisher() override;
  SnapshotPublisher(const SnapshotPublisher&) = delete;
  SnapshotPublisher& operator=(const SnapshotPublisher&) = delete;

  void onStart(const run::RunStart& start) override;
  void onFrame(const run::FrameSnapshot& frame) override;
  // Publishes the final map, the corrected trajectory, the aligned ground truth and the summary, then the thread
  // ends (the LiveState stays as it is for the server).
  void onEnd(const std::vector<io::StampedPose>& trajectory, const report::RunInfo& info) override;

  // Snapshots replaced by a newer one before the thread took them.
  std::size_t droppedSnapshots() const;

  // The growing dense cloud of the run (whole replacement): `xyz` 3 floats per point (world frame, metres), `rgb`
  // 3 bytes per point. Thread-safe, from any thread (the fusion's own); returns at once: it only keeps the cloud
  // as the newest one (replacing one not yet published) and wakes the publishing thread, which thins it
  // (dense_max_points), encodes it and hands it to the browsers at most every dense_period. Before onStart and
  // after onEnd it is published at once in the caller's thread (the final cloud of a run). Throws core::Error
  // when the sizes do not match (xyz.size() == rgb.size(), a multiple of 3).
  void publishDenseCloud(std::vector<float> xyz, std::vector<std::uint8_t> rgb);

 private:
  using Clock = std::chrono::steady_clock;
  void run();
  void stopThread();
  void publishFrame(const run::FrameSnapshot& frame, std::vector<TrajectoryPoint> poses, bool with_map);
  void publishDense(ColouredGeometry cloud);
  MapDelta mapDelta();

  LiveState& state_;
  PublisherOptions options_;
  mutable std::mutex mutex_;  // guards the hand-off below
  std::condition_variable wake_;
  std::optional<run::FrameSnapshot> latest_;
  std::vector<TrajectoryPoint> new_poses_;
  bool stop_ = false;
  bool running_ = false;  // the publishing thread takes the dense clouds (else publishDenseCloud does)
  std::optional<ColouredGeometry> pending_dense_;
  std::size_t dropped_ = 0;
  std::mutex map_mutex_;  // guards map_: onEnd releases it while the thread may be reading the map
  std::shared_ptr<const map::Map> map_;
  // Used by the publishing thread only (and by onEnd after it ended).
  MapSnapshot last_map_;
  std::vector<io::StampedPose> ground_truth_, estimate_;
  Clock::time_point last_map_time_{}, last_alignment_time_{}, last_dense_time_{};
  std::size_t last_processed_ = 0;
  double last_elapsed_s_ = 0;
  std::thread thread_;
};

}  // namespace amos::viewer
