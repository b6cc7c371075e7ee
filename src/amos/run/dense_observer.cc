#include "amos/dense/dense_observer.h"

#include <spdlog/spdlog.h>

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

#include "amos/dense/dense_outputs.h"

namespace amos::dense {

DenseObserver::DenseObserver(const DenseOptions& options, std::string output_dir, LiveCloudCallback on_live_cloud)
    : options_(options), output_dir_(std::move(output_dir)), on_live_cloud_(std::move(on_live_cloud)) {
  options_.check();
}

DenseObserver::~DenseObserver() = default;

std::vector<std::string> DenseObserver::outputNames() { return denseOutputNames(); }

void DenseObserver::onStart(const run::RunStart& start) {
  mapper_ = std::make_unique<DenseMapper>(options_, start.camera, on_live_cloud_);
}

void DenseObserver::onFrame(const run::FrameSnapshot& frame) {
  if (!mapper_ || frame.state != tracking::TrackingState::kOk || frame.frame.depth.empty()) return;
  mapper_->push({frame.timestamp, frame.T_cw, {frame.frame.depth, frame.frame.bgr, frame.dynamic_mask}});
}

void DenseObserver::onStreamEnd() {
  if (mapper_) mapper_->finish();
}

void DenseObserver::addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) {
  if (!mapper_) return;
  mapper_->finish();  // no-op when onStreamEnd did it; a run that failed before never called onStreamEnd
  const DenseMap map = mapper_->fuseFinal(trajectory);
  writeDenseOutputs(output_dir_, map);
  // The viewer gets the final map's cloud (final trajectory), so what it shows after the run agrees with
  // trajectory.txt and mesh.ply, not with the live volume's tracking poses.
  if (on_live_cloud_ && map.cloud) {
    LiveCloud final_cloud = liveCloudOf(*map.cloud, options_.live_cloud_voxel);
    final_cloud.frames_fused = map.stats["frames_fused"].get<std::size_t>();
    on_live_cloud_(final_cloud);
  }
  info.sections["dense"] = map.stats;
  spdlog::info("dense map: {} frames fused, {} mesh vertices, {} removed points, floor {}; in {:.1f} s",
               map.stats["frames_fused"].get<std::size_t>(), map.mesh->vertices_.size(),
               map.removed->points_.size(), map.floor ? "found" : "not found", map.stats["final_s"].get<double>());
  mapper_.reset();  // the kept frames' memory
}

}  // namespace amos::dense
