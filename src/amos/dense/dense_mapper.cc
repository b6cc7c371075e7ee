#include "amos/dense/dense_mapper.h"

#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/core/thread_priority.h"
#include "amos/dense/free_space_carving.h"
#include "amos/dense/open3d_geometry.h"
#include "amos/dense/tsdf_volume.h"
#include "amos/dense/voxel_mean_cloud.h"
#include "amos/io/poses_by_stamp.h"

namespace amos::dense {

namespace {

using core::threadCpuMs;  // what fusion costs the machine, whatever else runs beside it

const DenseOptions& checked(const DenseOptions& options, const core::CameraIntrinsics& camera) {
  options.checkFor(camera);
  return options;
}

nlohmann::json summary(const std::vector<double>& ms) {
  if (ms.empty()) return {{"count", 0}};
  double sum = 0;
  for (double v : ms) sum += v;
  return {{"count", ms.size()},
          {"median_ms", core::percentile(ms, 0.5)},
          {"p95_ms", core::percentile(ms, 0.95)},
          {"mean_ms", sum / static_cast<double>(ms.size())}};
}

// The readings of `removed` (every `step`-th pixel) as world points with their colours.
void addRemovedPoints(const PreparedFrame& frame, const core::CameraIntrinsics& camera, const core::SE3& T_wc,
                      int step, VoxelMeanCloud& out) {
  for (int v = 0; v < frame.removed.rows; v += step) {
    for (int u = 0; u < frame.removed.cols; u += step) {
      const float z = frame.removed.at<float>(v, u);
      if (z <= 0) continue;
      const Eigen::Vector3d p_c((u - camera.cx) * z / camera.fx, (v - camera.cy) * z / camera.fy, z);
      const cv::Vec3b bgr = frame.bgr.at<cv::Vec3b>(v, u);
      out.add(T_wc * p_c, Eigen::Vector3d(bgr[2] / 255.0, bgr[1] / 255.0, bgr[0] / 255.0));
    }
  }
}

LiveCloud downsampledLiveCloud(const open3d::geometry::PointCloud& surface, double voxel) {
  const auto cloud = surface.VoxelDownSample(voxel);
  LiveCloud out;
  out.points.reserve(cloud->points_.size());
  out.colours.reserve(cloud->points_.size());
  for (std::size_t i = 0; i < cloud->points_.size(); ++i) {
    out.points.push_back(cloud->points_[i].cast<float>());
    const Eigen::Vector3d c = cloud->HasColors() ? cloud->colors_[i] : Eigen::Vector3d(0.5, 0.5, 0.5);
    out.colours.push_back({static_cast<std::uint8_t>(std::lround(255 * std::clamp(c.x(), 0.0, 1.0))),
                           static_cast<std::uint8_t>(std::lround(255 * std::clamp(c.y(), 0.0, 1.0))),
                           static_cast<std::uint8_t>(std::lround(255 * std::clamp(c.z(), 0.0, 1.0)))});
  }
  return out;
}

void stopIfAsked(const std::atomic<bool>* stop) {
  if (stop != nullptr && stop->load()) throw FusionStopped();
}

nlohmann::json floorJson(const FloorPlane& floor) {
  return {{"normal", {floor.normal.x(), floor.normal.y(), floor.normal.z()}},
          {"offset", floor.offset},
          {"support_points", floor.support},
          {"camera_height_m", floor.camera_height}};
}

}  // namespace

struct DenseMapper::LiveStats {
  std::vector<double> thread_cpu_ms;     // per frame taken from the queue: preparation, compression, live fusion
  std::vector<double> live_integrate_ms; // per live-fused frame
  std::vector<double> live_cloud_ms;     // per live cloud handed to the callback
  std::size_t live_fused = 0;
  std::size_t kept_bytes = 0;
  std::chrono::steady_clock::time_point last_cloud{};
};

DenseMapper::DenseMapper(const DenseOptions& options, const core::CameraIntrinsics& camera,
                         LiveCloudCallback on_live_cloud)
    : options_(checked(options, camera)),
      preparer_(camera, options),
      on_live_cloud_(std::move(on_live_cloud)),
      live_(options.live_every > 0 ? std::make_unique<TsdfVolume>(options) : nullptr),
      live_stats_(std::make_unique<LiveStats>()),
      queue_(static_cast<std::size_t>(options.queue_frames)),
      thread_([this] { fusionLoop(); }) {}

DenseMapper::~DenseMapper() {
  queue_.close();
  if (thread_.joinable()) thread_.join();
}

bool DenseMapper::push(DenseFrame frame) {
  const std::size_t index = pushed_++;
  if (index % static_cast<std::size_t>(options_.frame_step) != 0) return true;
  // The run's thread is the one producer: with room now, push() cannot block.
  if (queue_.size() >= static_cast<std::size_t>(options_.queue_frames) || !queue_.push(std::move(frame))) {
    ++dropped_;
    return false;
  }
  return true;
}

void DenseMapper::fusionLoop() {
  serialOpenMpInThisThread();
  core::lowerThisThreadPriority(core::kBackgroundNice);
  while (std::optional<DenseFrame> frame = queue_.pop()) {
    if (failure_) continue;  // drain after an error; finish() reports it
    try {
      process(*frame);
    } catch (...) {
      failure_ = std::current_exception();
    }
  }
}

void DenseMapper::process(const DenseFrame& frame) {
  const double start = threadCpuMs();
  const PreparedFrame prepared = preparer_.prepare(frame.images);
  kept_.push_back(compressFrame(prepared, frame.timestamp, frame.T_cw));
  live_stats_->kept_bytes += kept_.back().bytes();
  if (live_ && (kept_.size() - 1) % static_cast<std::size_t>(options_.live_every) == 0) {
    const double before = threadCpuMs();
    live_->integrate(prepared.depth, prepared.bgr, preparer_.intrinsics(), frame.T_cw);
    live_stats_->live_integrate_ms.push_back(threadCpuMs() - before);
    ++live_stats_->live_fused;
    publishLiveCloud();
  }
  live_stats_->thread_cpu_ms.push_back(threadCpuMs() - start);
}

LiveCloud liveCloudOf(const DenseCloud& surface, double voxel) {
  return downsampledLiveCloud(open3dCloud(surface), voxel);
}

std::shared_ptr<const LiveCloud> DenseMapper::liveSnapshot() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex_);
  return snapshot_;
}

void DenseMapper::publishLiveCloud() {
  const auto now = std::chrono::steady_clock::now();
  if (live_stats_->live_fused > 1 && now - live_stats_->last_cloud < std::chrono::duration<double>(options_.live_period_s))
    return;
  live_stats_->last_cloud = now;
  const double start = threadCpuMs();
  auto out = std::make_shared<LiveCloud>(downsampledLiveCloud(*live_->extractCloud(), options_.live_cloud_voxel));
  out->frames_fused = live_stats_->live_fused;
  {
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    snapshot_ = out;
  }
  if (on_live_cloud_) on_live_cloud_(*out);
  live_stats_->live_cloud_ms.push_back(threadCpuMs() - start);
}

void DenseMapper::finish() {
  queue_.close();
  if (thread_.joinable()) thread_.join();
  if (failure_) std::rethrow_exception(failure_);
}

DenseMap DenseMapper::fuseFinal(const std::atomic<bool>* stop) const {
  std::vector<io::StampedPose> as_pushed;
  as_pushed.reserve(kept_.size());
  for (const StoredFrame& frame : kept_) as_pushed.push_back({frame.timestamp, frame.T_cw.inverse()});
  return fuseFinal(as_pushed, stop);
}

DenseMap DenseMapper::fuseFinal(const std::vector<io::StampedPose>& trajectory, const std::atomic<bool>* stop) const {
  core::require(!thread_.joinable(), "DenseMapper::fuseFinal before finish()");
  // In a thread of its own with serial OpenMP (tsdf_volume.h): Open3D's spinning OpenMP threads made the final
  // fusion slower on two cores than one thread is (Bonn-like synthetic run on a loaded machine: 42 ms median,
  // 82 ms mean per frame against 13 ms), and the caller's thread keeps its own OpenMP settings.
  DenseMap map;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      serialOpenMpInThisThread();
      map = fuseFinalHere(trajectory, stop);
    } catch (...) {
      failure = std::current_exception();
    }
  });
  worker.join();
  if (failure) std::rethrow_exception(failure);
  return map;
}

nlohmann::json DenseMapper::carveFreeSpace(TsdfVolume& volume,
                                           const std::vector<std::pair<const StoredFrame*, core::SE3>>& fused,
                                           const std::atomic<bool>* stop, VoxelMeanCloud& removed) const {
  auto carver = FreeSpaceCarver::ofSurface(volume, seeThroughOptionsOf(options_));
  for (const auto& [stored, T_wc] : fused) {
    stopIfAsked(stop);
    carver.addFrame(decompressDepth(*stored), preparer_.intrinsics(), T_wc.inverse());
  }
  const CarveResult carved = carver.carve(volume);
  // What was carved was left out of the map as the dynamic readings were: it joins the removed points.
  for (std::size_t i = 0; i < carved.points.size(); ++i) removed.add(carved.points[i], carved.colours[i]);
  return {{"vertices_voted", carved.vertices_voted},
          {"vertices_carved", carved.points.size()},
          {"voxels_forgotten", carved.voxels_forgotten},
          {"frames", carved.frames}};
}

DenseMap DenseMapper::fuseFinalHere(const std::vector<io::StampedPose>& trajectory,
                                    const std::atomic<bool>* stop) const {
  core::Stopwatch total;
  const io::PosesByStamp poses = io::posesByStamp(trajectory);
  const core::CameraIntrinsics& camera = preparer_.intrinsics();
  TsdfVolume volume(options_);
  DenseMap map;
  VoxelMeanCloud removed(options_.voxel_size);
  std::vector<double> integrate_ms;
  std::vector<Eigen::Vector3d> centres, down_axes, forward_axes;
  std::vector<std::pair<const StoredFrame*, core::SE3>> fused;  // with their final poses T_wc
  for (const StoredFrame& stored : kept_) {
    stopIfAsked(stop);
    // In-memory stamps: the same frame's are equal up to floating-point rounding.
    const core::SE3* T_wc = io::poseNear(poses, stored.timestamp, 1e-6);
    if (T_wc == nullptr) continue;  // not in the final trajectory
    fused.emplace_back(&stored, *T_wc);
    const PreparedFrame frame = decompressFrame(stored);
    core::Stopwatch watch;
    volume.integrate(frame.depth, frame.bgr, camera, T_wc->inverse());
    integrate_ms.push_back(watch.elapsedMs());
    addRemovedPoints(frame, camera, *T_wc, 2, removed);
    centres.push_back(T_wc->translation());
    down_axes.push_back(T_wc->linear().col(1));
    forward_axes.push_back(T_wc->linear().col(2));
  }
  core::Stopwatch watch;
  nlohmann::json carve_stats = nullptr;
  if (options_.carve) {
    carve_stats = carveFreeSpace(volume, fused, stop, removed);
    carve_stats["ms"] = watch.elapsedMs();
  }
  map.removed = removed.cloud();
  stopIfAsked(stop);
  watch.restart();
  map.mesh = plainMesh(*volume.extractMesh());  // colours clamped to bytes: the TSDF's averages can step past 1
  const double mesh_ms = watch.elapsedMs();
  stopIfAsked(stop);
  watch.restart();
  map.cloud = plainCloud(*volume.extractCloud());
  const double cloud_ms = watch.elapsedMs();
  stopIfAsked(stop);
  watch.restart();
  // The floor plan is one product among four: when it fails, the mesh and the clouds are still the map's.
  try {
    map.floor = findFloor(map.cloud.points, centres, down_axes);
    if (map.floor) {
      Eigen::Vector3d forward = Eigen::Vector3d::Zero();
      for (const auto& f : forward_axes) forward += f;
      map.grid = buildOccupancyGrid(map.cloud.points, *map.floor, centres.front(), forward, options_);
    }
  } catch (const std::exception& e) {
    map.grid.reset();
    map.floor_plan_error = e.what();
  }
  const double floor_ms = watch.elapsedMs();
  const LiveStats& live = *live_stats_;
  nlohmann::json& s = map.stats;
  s["frames_tracked"] = pushed_;
  s["frames_kept"] = kept_.size();
  s["frames_dropped"] = dropped_;
  s["frames_fused"] = integrate_ms.size();
  s["kept_frames_mb"] = static_cast<double>(live.kept_bytes) / 1e6;
  s["live"] = {{"frames_fused", live.live_fused},
               {"thread_cpu_per_frame", summary(live.thread_cpu_ms)},
               {"integrate", summary(live.live_integrate_ms)},
               {"cloud", summary(live.live_cloud_ms)},
               {"volume_mb", live_ ? static_cast<double>(live_->bytes()) / 1e6 : 0.0}};
  s["fusion_per_frame"] = summary(integrate_ms);  // wall ms, one thread
  s["carving"] = carve_stats;
  s["blocks"] = volume.blocks();
  s["voxels"] = volume.voxels();
  s["volume_mb"] = static_cast<double>(volume.bytes()) / 1e6;
  s["mesh"] = {{"vertices", map.mesh.vertices.size()}, {"triangles", map.mesh.triangles.size()},
               {"extraction_ms", mesh_ms}};
  s["cloud"] = {{"points", map.cloud.points.size()}, {"extraction_ms", cloud_ms}};
  s["removed_points"] = map.removed.points.size();
  s["floor"] = map.floor ? floorJson(*map.floor) : nlohmann::json(nullptr);
  if (map.grid) {
    s["occupancy"] = {{"width", map.grid->width}, {"height", map.grid->height},
                      {"resolution_m", map.grid->resolution}, {"free", map.grid->count(kFreeCell)},
                      {"occupied", map.grid->count(kOccupiedCell)}, {"unknown", map.grid->count(kUnknownCell)}};
  }
  if (!map.floor_plan_error.empty()) s["floor_plan_error"] = map.floor_plan_error;
  s["floor_and_grid_ms"] = floor_ms;
  s["final_s"] = total.elapsedMs() / 1000.0;
  return map;
}

}  // namespace amos::dense
