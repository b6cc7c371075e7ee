#include "amos/api/dense_feed.h"

#include "amos/core/error.h"

#ifdef AMOS_HAVE_OPEN3D
#include "amos/api/dense_conversion.h"
#include "amos/dense/dense_mapper.h"
#include "amos/dense/floor_plane.h"
#include "amos/dense/occupancy_grid.h"
#endif

namespace amos::api {

#ifdef AMOS_HAVE_OPEN3D

struct DenseFeed::Impl {
  dense::DenseOptions options;
  dense::DenseMapper mapper;
  explicit Impl(const config::Settings& settings)
      : options(settings.section<dense::DenseOptions>()), mapper(options, settings.camera) {}
};

DenseFeed::DenseFeed(const config::Settings& settings) : impl_(std::make_unique<Impl>(settings)) {}

void DenseFeed::push(const system::ProcessedFrame& out) {
  // As run/dense_observer.cc's onFrame: the tracked frames with depth, their tracking pose and dynamic mask.
  if (out.slam.track.state != tracking::TrackingState::kOk || out.frame.depth.empty()) return;
  impl_->mapper.push({out.frame.timestamp, out.slam.track.T_cw, {out.frame.depth, out.frame.bgr, out.dynamic_mask}});
}

void DenseFeed::finish() { impl_->mapper.finish(); }

DenseMap DenseFeed::fuse(const std::vector<io::StampedPose>& trajectory) const {
  return publicDenseMap(impl_->mapper.fuseFinal(trajectory));
}

std::optional<DenseSnapshot> DenseFeed::snapshot() const {
  const std::shared_ptr<const dense::LiveCloud> live = impl_->mapper.liveSnapshot();
  if (!live) return std::nullopt;
  return publicSnapshot(*live);
}

std::optional<OccupancyGrid> DenseFeed::liveGrid(const std::vector<io::StampedPose>& trajectory) const {
  const std::shared_ptr<const dense::LiveCloud> live = impl_->mapper.liveSnapshot();
  if (!live || trajectory.empty()) return std::nullopt;
  std::vector<Eigen::Vector3d> points;
  points.reserve(live->points.size());
  for (const Eigen::Vector3f& p : live->points) points.push_back(p.cast<double>());
  // The cameras as the final fusion places its floor plan: centres, image-down axes, mean viewing direction.
  std::vector<Eigen::Vector3d> centres, down_axes;
  Eigen::Vector3d forward = Eigen::Vector3d::Zero();
  for (const io::StampedPose& pose : trajectory) {
    centres.push_back(pose.T_wc.translation());
    down_axes.push_back(pose.T_wc.linear().col(1));
    forward += pose.T_wc.linear().col(2);
  }
  const std::optional<dense::FloorPlane> floor = dense::findFloor(points, centres, down_axes);
  if (!floor) return std::nullopt;
  return publicGrid(dense::buildOccupancyGrid(points, *floor, centres.front(), forward, impl_->options), *floor);
}

#else  // built without Open3D: Options::dense is refused when the Slam is made

struct DenseFeed::Impl {};

DenseFeed::DenseFeed(const config::Settings&) {
  throw core::Error(
      "amos::Options::dense: this library was built without the dense map (Open3D; install libopen3d-dev and "
      "rebuild)");
}

void DenseFeed::push(const system::ProcessedFrame&) {}
void DenseFeed::finish() {}
DenseMap DenseFeed::fuse(const std::vector<io::StampedPose>&) const { return {}; }
std::optional<DenseSnapshot> DenseFeed::snapshot() const { return std::nullopt; }
std::optional<OccupancyGrid> DenseFeed::liveGrid(const std::vector<io::StampedPose>&) const { return std::nullopt; }

#endif

DenseFeed::~DenseFeed() = default;

}  // namespace amos::api
