#include "amos/system/slam_system.h"

#include <spdlog/spdlog.h>

#include <shared_mutex>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/mapping/local_bundle_adjustment.h"

namespace amos::system {

void SlamOptions::check() const {
  camera.check();
  sensor.check();
  orb.check();
  tracking.check();
  mapping.check();
  loop.check();
  core::requireAtLeast(covisibility.min_weight, "covisibility.min_weight", 1);
}

SlamSystem::SlamSystem(const SlamOptions& options)
    : options_(options),
      sensor_((options.check(), std::make_shared<map::Sensor>(options.camera, options.sensor, options.orb))),
      map_(std::make_shared<map::Map>(options.covisibility)) {
  if (options_.vocabulary) places_ = std::make_shared<place::KeyFrameDatabase>(options_.vocabulary);
  loop_closer_ = std::make_unique<loop::LoopCloser>(options_.loop, map_, options_.loop.bag_of_words ? places_ : nullptr);
  mapper_ = std::make_unique<mapping::LocalMapper>(
      options_.mapping, map_, options_.deterministic, &times_,
      [closer = loop_closer_.get(), places = places_.get(), times = &times_, map = map_.get(),
       global_ba = options_.loop.global_bundle_adjustment, ba = options_.mapping.ba,
       after = options_.after_keyframe](const map::KeyFramePtr& kf) {
        // A keyframe joins the place database once mapped (its descriptors never change), before the loop search.
        if (places) {
          core::Stopwatch watch;
          places->add(kf->id(), places->transform(kf->features().descriptors));
          times->add("place.add_keyframe", watch.elapsedMs());
        }
        if (closer->process(kf) && global_ba) {
          core::Stopwatch watch;
          const mapping::BaStats stats = mapping::runGlobalBundleAdjustment(*map, ba, nullptr);
          times->add("loop.global_ba", watch.elapsedMs());
          spdlog::info("global bundle adjustment after the loop: {} keyframes, {} points, {} outliers removed, "
                       "{:.0f} ms",
                       stats.adjusted_keyframes, stats.points, stats.outliers_removed, watch.elapsedMs());
        }
        if (after) after(kf);
      });
  tracker_ = std::make_unique<tracking::Tracker>(options_.tracking, map_, mapper_.get(), &times_, places_);
}

SlamSystem::~SlamSystem() { finish(); }

FrameOutput SlamSystem::track(const TrackInput& input) {
  core::require(!finished_, "SlamSystem: frame given after finish()");
  mapper_->rethrowIfFailed();  // the frame boundary where a mapping failure reaches the caller
  core::require(input.depth.type() == CV_32F, "SlamSystem: depth image must be CV_32F metres");
  core::require(map_loaded_ || !options_.tracking.localization_only,
                "SlamSystem: localization mode needs a loaded map (--load-map FILE)");
  const ExtractedFeatures& features = input.features;
  core::Stopwatch total, watch;
  FrameOutput out;
  out.extract_ms = features.extract_ms;
  map::FrameBuildStats build;
  auto built = map::buildFrameFeatures(*sensor_, features.keypoints, features.descriptors, input.depth,
                                       input.dynamic_mask, &build);
  map::Frame f = map::makeFrame(next_frame_id_++, input.timestamp, sensor_, std::move(built),
                                map::makeThumbnail(features.gray), input.dynamic_mask);
  f.depth_image = input.depth;
  f.gray = features.gray;
  out.build_ms = watch.elapsedMs();
  watch.restart();
  out.track = tracker_->track(std::move(f), input.initial_T_cw);
  out.track_ms = watch.elapsedMs();
  out.view.state = tracker_->state();
  out.view.velocity = tracker_->velocity();
  out.view.reference_kf = tracker_->referenceKeyFrameId();
  if (input.reference_keyframe_view) {
    out.view.reference_keyframe =
        std::make_shared<const tracking::ReferenceKeyFrameView>(tracker_->referenceKeyFrameView());
  }
  out.keypoints = build.extracted - build.removed_dynamic;
  out.removed_dynamic = build.removed_dynamic;
  out.with_depth = build.with_depth;
  out.total_ms = total.elapsedMs() + features.extract_ms;

  times_.add("frame.extract", out.extract_ms);
  times_.add("frame.build", out.build_ms);
  times_.add("frame.track", out.track_ms);
  times_.add("frame.total", out.total_ms);

  ++stats_.frames;
  switch (out.track.state) {
    case tracking::TrackingState::kOk: ++stats_.tracked; break;
    case tracking::TrackingState::kLost: ++stats_.lost; break;
    case tracking::TrackingState::kNotInitialized: ++stats_.not_initialized; break;
  }
  stats_.relocalized += out.track.relocalized;
  stats_.keyframes_created += out.track.new_keyframe;
  FrameRecord record;
  record.timestamp = input.timestamp;
  record.state = out.track.state;
  record.reference_kf = out.track.reference_kf;
  record.T_cr = out.track.T_cr;
  records_.push_back(record);
  return out;
}

mapio::MapFileSummary SlamSystem::loadMap(const std::string& path) {
  core::require(records_.empty() && !map_loaded_, "SlamSystem::loadMap: only before the first frame, once");
  const mapio::MapFileSummary summary = mapio::loadMap(path, sensor_, *map_);
  if (places_) {
    std::shared_lock lock(map_->mutex());
    for (const auto& kf : map_->keyFrames()) places_->add(kf->id(), places_->transform(kf->features().descriptors));
  }
  // Frame ids go on after the loaded ones: map points and keyframes remember the frame they came from.
  next_frame_id_ = summary.max_frame_id + 1;
  map_loaded_ = true;
  return summary;
}

mapio::MapFileSummary SlamSystem::saveMap(const std::string& path) const { return mapio::saveMap(path, *map_, *sensor_); }

void SlamSystem::finish() {
  if (finished_) return;
  finished_ = true;
  mapper_->stop();
}

std::exception_ptr SlamSystem::workerFailure() const { return mapper_->failure(); }

std::vector<io::StampedPose> SlamSystem::trajectory() const {
  std::vector<io::StampedPose> out;
  out.reserve(records_.size());
  std::shared_lock lock(map_->mutex());
  for (const FrameRecord& r : records_) {
    if (r.reference_kf == map::kNoKeyFrame) continue;  // before the map existed
    if (options_.tracking.localization_only && r.state != tracking::TrackingState::kOk) continue;
    const core::SE3 T_cw = r.T_cr * map_->keyFramePose(r.reference_kf);
    out.push_back({r.timestamp, T_cw.inverse()});
  }
  return out;
}

std::vector<io::StampedPose> SlamSystem::keyframeTrajectory() const {
  std::vector<io::StampedPose> out;
  std::shared_lock lock(map_->mutex());
  for (const auto& kf : map_->keyFrames()) {
    if (!kf->isBad()) out.push_back({kf->timestamp(), kf->T_wc()});
  }
  return out;
}

std::vector<Eigen::Vector3d> SlamSystem::mapPointPositions() const {
  std::vector<Eigen::Vector3d> out;
  std::shared_lock lock(map_->mutex());
  for (const auto& p : map_->mapPoints()) {
    if (!p->isBad()) out.push_back(p->position());
  }
  return out;
}

SlamStats SlamSystem::stats() const {
  SlamStats s = stats_;
  {
    std::shared_lock lock(map_->mutex());
    s.keyframes = map_->numKeyFrames();
    s.map_points = map_->numMapPoints();
  }
  s.mapping = mapper_->stats();
  s.loops_closed = loop_closer_->closures().size();
  return s;
}

}  // namespace amos::system
