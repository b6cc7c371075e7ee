#include "amos/run/dense_observer.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <functional>

#include "amos/dense/dense_map_files.h"

namespace amos::run {

namespace fs = std::filesystem;

DenseObserver::DenseObserver(const dense::DenseOptions& options, std::string output_dir,
                             dense::LiveCloudCallback on_live_cloud)
    : options_(options), output_dir_(std::move(output_dir)), on_live_cloud_(std::move(on_live_cloud)) {
  options_.check();
}

DenseObserver::~DenseObserver() = default;

std::vector<std::string> DenseObserver::outputNames() {
  return {"mesh.ply", "cloud.ply", "removed_points.ply", "occupancy.pgm", "occupancy.yaml"};
}

void DenseObserver::onStart(const RunStart& start) {
  mapper_ = std::make_unique<dense::DenseMapper>(options_, start.camera, on_live_cloud_);
}

void DenseObserver::onFrame(const FrameSnapshot& frame) {
  if (!mapper_ || frame.state != tracking::TrackingState::kOk || frame.frame.depth.empty()) return;
  mapper_->push({frame.timestamp, frame.T_cw, {frame.frame.depth, frame.frame.bgr, frame.dynamic_mask}});
}

void DenseObserver::onStreamEnd() {
  if (mapper_) mapper_->finish();
}

nlohmann::json DenseObserver::writeFiles(const dense::DenseMap& map, std::vector<std::string>& failures) const {
  const fs::path dir(output_dir_);
  nlohmann::json files = nlohmann::json::object();
  auto write = [&](const std::string& name, const std::function<void(const std::string&)>& writer) {
    try {
      writer((dir / name).string());
      files[name] = "written";
    } catch (const std::exception& e) {
      files[name] = std::string("failed: ") + e.what();
      failures.push_back(fmt::format("{}: {}", name, e.what()));
    }
  };
  write("mesh.ply", [&](const std::string& path) { dense::writeMeshPly(path, map.mesh); });
  write("cloud.ply", [&](const std::string& path) { dense::writeCloudPly(path, map.cloud); });
  write("removed_points.ply", [&](const std::string& path) { dense::writeCloudPly(path, map.removed); });
  if (map.grid && map.floor) {
    write("occupancy.yaml", [&](const std::string& path) { dense::writeFloorPlan(path, *map.grid, *map.floor); });
  } else if (!map.floor_plan_error.empty()) {
    files["occupancy.yaml"] = "failed: " + map.floor_plan_error;
    failures.push_back("floor plan: " + map.floor_plan_error);
  } else {
    files["occupancy.yaml"] = "none: no floor found";
  }
  return files;
}

report::OptionalStage DenseObserver::finishMap(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info,
                                               const std::atomic<bool>* stop) {
  using Status = report::OptionalStage::Status;
  if (!mapper_) return {Status::kSkipped, "the run never started"};
  try {
    mapper_->finish();  // no-op when onStreamEnd did it; a run that failed before never called onStreamEnd
    const dense::DenseMap map = mapper_->fuseFinal(trajectory, stop);
    mapper_.reset();  // the kept frames' memory, before the files are made
    std::vector<std::string> failures;
    nlohmann::json stats = map.stats;
    stats["files"] = writeFiles(map, failures);
    info.sections["dense"] = stats;
    // The viewer gets the final map's cloud (final trajectory), so what it shows after the run agrees with
    // trajectory.txt and mesh.ply, not with the live volume's tracking poses.
    if (on_live_cloud_) {
      dense::LiveCloud final_cloud = dense::liveCloudOf(map.cloud, options_.live_cloud_voxel);
      final_cloud.frames_fused = map.stats["frames_fused"].get<std::size_t>();
      on_live_cloud_(final_cloud);
    }
    spdlog::info("dense map: {} frames fused, {} mesh vertices, {} removed points, floor {}; in {:.1f} s",
                 map.stats["frames_fused"].get<std::size_t>(), map.mesh.vertices.size(), map.removed.points.size(),
                 map.floor ? "found" : "not found", map.stats["final_s"].get<double>());
    if (failures.empty()) return {Status::kDone, ""};
    return {Status::kFailed, fmt::format("{}", fmt::join(failures, "; "))};
  } catch (const dense::FusionStopped&) {
    mapper_.reset();
    return {Status::kInterrupted, "stopped during the final fusion; no dense file written"};
  } catch (const std::exception& e) {
    mapper_.reset();
    return {Status::kFailed, e.what()};
  }
}

}  // namespace amos::run
