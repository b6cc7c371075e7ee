#include "amos/api/dense_feed.h"

#include "amos/core/error.h"

#ifdef AMOS_HAVE_OPEN3D
#include "amos/api/dense_conversion.h"
#include "amos/dense/dense_mapper.h"
#endif

namespace amos::api {

#ifdef AMOS_HAVE_OPEN3D

struct DenseFeed::Impl {
  dense::DenseMapper mapper;
  explicit Impl(const config::Settings& settings)
      : mapper(settings.section<dense::DenseOptions>(), settings.camera) {}
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

#endif

DenseFeed::~DenseFeed() = default;

}  // namespace amos::api
