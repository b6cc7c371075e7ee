#pragma once
// Dense fusion of the static world beside tracking, and the final map.
//
// Poses change after the fact (local bundle adjustment, loop closing). Choice (b) of issue 43: the frames are fused
// live with their tracking poses, for the live view only, and the final map is fused anew at the end of the run
// with the final trajectory, from every kept frame (Dense.frameStep). Why not fuse against keyframes and
// re-integrate what a correction moved: that needs the TSDF's de-integration (Open3D's volumes have none) or a
// volume per keyframe (memory grows with the keyframes, and merging them costs what re-fusion costs), and a loop
// closure moves every keyframe anyway. Re-fusing a frame costs ~25 ms of one core (Bonn, Dense.scale 0.5), about
// what tracking it cost; after the run both cores are free for it. So the final mesh agrees with the final
// trajectory by construction, and the live volume can be cheap (a subset of frames: Dense.liveEvery).
// The kept frames (static depth, left-out dynamic depth, colour, at Dense.scale) are held compressed in memory
// (frame_store.h, ~100 kB a frame at 0.5): this works for a live camera too, where nothing can be read again.
//
// Threads: push() is called in the run's thread and never waits: the frame's images are shared (the run never
// writes them after reading), the queue is bounded (Dense.queueFrames) and a frame that finds it full is dropped
// and counted. The fusion thread (nice +10, OpenMP regions serial: tsdf_volume.h) prepares each frame
// (frame_preparation.h), compresses it into the store and, every Dense.liveEvery-th, fuses it into the live
// volume; at most every Dense.livePeriod seconds it hands a downsampled coloured cloud of the live volume to the
// callback (in the fusion thread) and keeps it as the latest snapshot (liveSnapshot(), any thread). finish() drains
// the queue and joins the thread; fuseFinal() then runs in a thread of its own (serial OpenMP as well) while the
// caller waits, and gives the map as plain data (dense_map.h); dense_map_files.h writes it.
//
// Without the run loop (a program driving it itself):
//   DenseMapper mapper(options, camera);             // options.live_every > 0 for live snapshots
//   mapper.push({stamp, T_cw, {depth, bgr, dynamic_mask}});   // per tracked frame; never waits
//   mapper.liveSnapshot();                            // the live volume's surface so far, or nullptr
//   mapper.finish();
//   DenseMap map = mapper.fuseFinal();                // with the poses as pushed (or fuseFinal(final trajectory))
//   writeMeshPly("mesh.ply", map.mesh);  if (map.grid) writeFloorPlan("floor.yaml", *map.grid, *map.floor);
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include "amos/core/bounded_queue.h"
#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dense/dense_map.h"
#include "amos/dense/dense_options.h"
#include "amos/dense/frame_preparation.h"
#include "amos/dense/frame_store.h"
#include "amos/io/trajectory.h"

namespace amos::dense {

class TsdfVolume;
class VoxelMeanCloud;

struct DenseFrame {
  double timestamp = 0;
  core::SE3 T_cw = core::SE3::Identity();  // as tracked
  FrameImages images;
};

// A snapshot of the live volume's surface for a viewer, in the world frame of the tracking poses.
struct LiveCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<std::array<std::uint8_t, 3>> colours;  // R, G, B
  std::size_t frames_fused = 0;
};
using LiveCloudCallback = std::function<void(const LiveCloud&)>;
// A surface cloud downsampled to `voxel` (m), colours as bytes: what the viewer is handed.
LiveCloud liveCloudOf(const DenseCloud& surface, double voxel);

// Thrown by fuseFinal when its stop flag was set: the final fusion was abandoned.
struct FusionStopped : std::runtime_error {
  FusionStopped() : std::runtime_error("the final dense fusion was stopped") {}
};

class DenseMapper {
 public:
  DenseMapper(const DenseOptions& options, const core::CameraIntrinsics& camera, LiveCloudCallback on_live_cloud = {});
  ~DenseMapper();
  DenseMapper(const DenseMapper&) = delete;
  DenseMapper& operator=(const DenseMapper&) = delete;

  // A tracked frame. Keeps every Dense.frameStep-th; returns false when it was dropped (queue full).
  bool push(DenseFrame frame);
  // Fuses what is queued and stops the fusion thread; rethrows its error.
  void finish();
  // The final map from every kept frame whose time stamp the trajectory (T_wc) holds. After finish(). When `stop`
  // is given and becomes true, the fusion ends at the next frame or stage and throws FusionStopped.
  DenseMap fuseFinal(const std::vector<io::StampedPose>& trajectory, const std::atomic<bool>* stop = nullptr) const;
  // The same with the poses the frames were pushed with.
  DenseMap fuseFinal(const std::atomic<bool>* stop = nullptr) const;
  // The latest surface of the live volume (what the callback was last handed), or nullptr before the first one or
  // without a live volume (Dense.liveEvery 0). Any thread.
  std::shared_ptr<const LiveCloud> liveSnapshot() const;

 private:
  struct LiveStats;
  void fusionLoop();
  void process(const DenseFrame& frame);
  void publishLiveCloud();
  DenseMap fuseFinalHere(const std::vector<io::StampedPose>& trajectory, const std::atomic<bool>* stop) const;
  // Free-space carving of the final volume with the frames as fused (free_space_carving.h); the carved vertices
  // join `removed`. Returns its figures for stats.json.
  nlohmann::json carveFreeSpace(TsdfVolume& volume,
                                const std::vector<std::pair<const StoredFrame*, core::SE3>>& fused,
                                const std::atomic<bool>* stop, VoxelMeanCloud& removed) const;

  DenseOptions options_;
  FramePreparer preparer_;
  LiveCloudCallback on_live_cloud_;
  std::unique_ptr<TsdfVolume> live_;
  std::vector<StoredFrame> kept_;  // fusion thread until finish(), then the caller's
  std::unique_ptr<LiveStats> live_stats_;
  std::size_t pushed_ = 0, dropped_ = 0;  // run's thread
  std::exception_ptr failure_;
  mutable std::mutex snapshot_mutex_;
  std::shared_ptr<const LiveCloud> snapshot_;
  core::BoundedQueue<DenseFrame> queue_;
  std::thread thread_;  // last: started once the rest exists
};

}  // namespace amos::dense
