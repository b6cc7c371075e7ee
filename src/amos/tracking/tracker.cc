#include "amos/tracking/tracker.h"

#include <spdlog/spdlog.h>

#include <mutex>
#include <shared_mutex>

#include "amos/core/error.h"
#include "amos/tracking/frame_commit.h"
#include "amos/tracking/frame_matching.h"
#include "amos/tracking/keyframe_insertion.h"
#include "amos/tracking/local_map_refinement.h"
#include "amos/tracking/recovery.h"

namespace amos::tracking {

const char* toString(TrackingState state) {
  switch (state) {
    case TrackingState::kNotInitialized: return "not_initialized";
    case TrackingState::kOk: return "ok";
    case TrackingState::kLost: return "lost";
  }
  return "?";
}

Tracker::Tracker(const TrackerOptions& options, std::shared_ptr<map::Map> map, KeyFrameSink* sink,
                 core::StageTimes* times, std::shared_ptr<const place::KeyFrameDatabase> places)
    : options_(options),
      map_(std::move(map)),
      sink_(sink),
      times_(times),
      relocalizer_(options.relocalization, options.matching, options.pose, std::move(places)) {
  options_.check();
  core::require(map_ != nullptr, "Tracker: map must not be null");
}

std::optional<core::SE3> Tracker::lastPose() const {
  if (!last_frame_tracked_) return std::nullopt;
  return last_frame_.T_cw;
}

ReferenceKeyFrameView Tracker::referenceKeyFrameView() const {
  ReferenceKeyFrameView view;
  if (!reference_kf_) return view;
  std::shared_lock lock(map_->mutex());
  view.id = reference_kf_->id();
  view.T_cw = reference_kf_->T_cw();
  view.keypoints = reference_kf_->features().keys;
  view.points_w.assign(view.keypoints.size(), Eigen::Vector3d::Zero());
  view.has_point.assign(view.keypoints.size(), false);
  for (int i = 0; i < reference_kf_->size(); ++i) {
    const auto& p = reference_kf_->mapPoint(i);
    if (p && !p->isBad()) {
      view.points_w[i] = p->position();
      view.has_point[i] = true;
    }
  }
  return view;
}

// predict and match -> refine (local map, photometric) -> decide keyframe -> commit.
TrackResult Tracker::track(map::Frame frame, const std::optional<core::SE3>& external_T_cw) {
  prepare(frame);
  if (state_ == TrackingState::kNotInitialized && startsNewMap()) return initialize(frame);
  FrameOutcome outcome;
  {
    std::shared_lock lock(map_->mutex());
    core::Stopwatch watch;
    outcome = estimateInitialPose(frame, external_T_cw);
    recordTime("track.initial_pose", watch);
    if (outcome.tracked) outcome.tracked = trackLocalMap(frame, outcome.inliers);
    recordTime("track.local_map", watch);
    if (outcome.tracked && photometric_) refinePhotometrically(frame);
    updateMotion(frame, outcome);
    dropTemporaryMatches(frame);
    temporary_points_.clear();
    outcome.new_keyframe = outcome.tracked && needNewKeyFrame(frame, outcome.inliers);
  }
  dropOutlierMatches(frame);
  if (outcome.new_keyframe) createNewKeyFrame(frame);
  return commit(std::move(frame), outcome);
}

void Tracker::prepare(map::Frame& frame) {
  core::require(frame.features && frame.sensor, "Tracker::track: frame without features");
  if (options_.photometric && !photometric_) photometric_.emplace(frame.sensor->camera(), options_.photometric_options);
  if (frame.map_points.size() != frame.size()) frame.resetMatches();
}

bool Tracker::startsNewMap() {
  bool has_map = false;
  {
    std::shared_lock lock(map_->mutex());
    has_map = map_->numKeyFrames() > 0;
  }
  if (has_map) {
    state_ = TrackingState::kLost;
    return false;
  }
  core::require(!options_.localization_only, "Tracker: localization mode needs a loaded map (--load-map)");
  return true;
}

TrackResult Tracker::initialize(map::Frame& frame) {
  TrackResult result;
  const map::FrameFeatures& f = *frame.features;
  int with_depth = 0;
  for (std::size_t i = 0; i < f.size(); ++i) with_depth += f.hasDepth(static_cast<int>(i));
  if (with_depth <= options_.init_min_depth_points) {
    result.state = TrackingState::kNotInitialized;
    return result;
  }
  frame.setPose(core::SE3::Identity());
  NewKeyFrame created = insertFirstKeyFrame(*map_, frame, photometric_ ? &*photometric_ : nullptr);
  const map::KeyFramePtr kf = created.kf;
  spdlog::debug("map initialised from frame {} with {} points", frame.id, created.new_points.size());
  if (sink_) sink_->insertKeyFrame(kf, std::move(created.new_points));
  reference_kf_ = kf;
  frame.reference_kf = kf->id();
  last_keyframe_frame_ = frame.id;
  local_map_.reset(kf);
  state_ = TrackingState::kOk;
  velocity_.reset();
  last_T_cr_ = core::SE3::Identity();
  result.state = state_;
  result.initialized_map = true;
  result.new_keyframe = true;
  result.inliers = static_cast<int>(kf->trackedMapPoints(0));
  result.reference_kf = kf->id();
  last_frame_ = std::move(frame);
  last_frame_tracked_ = true;
  return result;
}

Tracker::FrameOutcome Tracker::estimateInitialPose(map::Frame& frame, const std::optional<core::SE3>& external_T_cw) {
  if (state_ == TrackingState::kOk) return followLastFrame(frame, external_T_cw);
  return relocalize(frame, external_T_cw);
}

Tracker::FrameOutcome Tracker::followLastFrame(map::Frame& frame, const std::optional<core::SE3>& external_T_cw) {
  FrameOutcome outcome;
  refreshLastFrame();
  if ((velocity_ || external_T_cw) && !relocalizedWithin(frame.id, 2)) {
    outcome.tracked = trackWithMotionModel(frame, external_T_cw, outcome.used_external_pose);
    if (!outcome.tracked) outcome.tracked = trackReferenceKeyFrame(frame);
  } else {
    outcome.tracked = trackReferenceKeyFrame(frame);
    // Right after a relocalisation the reference keyframe may share too few descriptors with the frame; the
    // relocalised pose itself (no velocity yet) is still a good prediction for a projection search.
    if (!outcome.tracked) outcome.tracked = trackWithMotionModel(frame, external_T_cw, outcome.used_external_pose);
  }
  // Both failed (in crowds: the narrow window's matches mostly on temporary points, too few in the map): the
  // recovery's wide window and PnP RANSAC over the local map, on this frame rather than after it is lost; its
  // local map tracking must then meet relocMinInliers.
  if (!outcome.tracked && options_.recovery_frames > 0 && last_tracked_ && recoverNearLastPose(frame, external_T_cw)) {
    outcome.tracked = true;
    markRelocalized(frame.id, outcome);
    spdlog::debug("frame {}: recovered in the same frame near the predicted pose", frame.id);
  }
  return outcome;
}

Tracker::FrameOutcome Tracker::relocalize(map::Frame& frame, const std::optional<core::SE3>& external_T_cw) {
  FrameOutcome outcome;
  const bool recently_lost = options_.recovery_frames > 0 && last_tracked_ &&
                             frame.id <= last_tracked_->frame + static_cast<map::FrameId>(options_.recovery_frames);
  if (recently_lost && recoverNearLastPose(frame, external_T_cw)) {
    outcome.tracked = true;
    spdlog::debug("frame {}: recovered near the last tracked pose", frame.id);
  } else {
    const map::KeyFramePtr kf = relocalizer_.relocalize(frame, *map_);
    outcome.tracked = kf != nullptr;
    if (kf) {
      reference_kf_ = kf;
      spdlog::debug("frame {}: relocalised against keyframe {}", frame.id, kf->id());
    }
  }
  if (outcome.tracked) markRelocalized(frame.id, outcome);
  return outcome;
}

void Tracker::refreshLastFrame() {
  map::Frame& last = last_frame_;
  // Points fused by local mapping since the last frame: follow them to the survivor.
  for (auto& p : last.map_points) {
    if (!p) continue;
    if (const auto replacement = p->replacedBy()) p = replacement;
  }
  // The reference keyframe may have moved (bundle adjustment) since the last frame was tracked.
  if (last.reference_kf != map::kNoKeyFrame && map_->knowsKeyFrame(last.reference_kf)) {
    last.setPose(last_T_cr_ * map_->keyFramePose(last.reference_kf));
  }
  if (last_keyframe_frame_ == last.id || !last_frame_tracked_) return;
  addTemporaryPoints(last, options_.vo_points_min, temporary_points_);
}

bool Tracker::trackWithMotionModel(map::Frame& frame, const std::optional<core::SE3>& external, bool& used_external) {
  const MotionHistory history{last_frame_.T_cw, last_frame_tracked_, velocity_};
  const MotionModelMatch match = tracking::trackWithMotionModel(
      frame, last_frame_, motionModelPredictions(history, external, options_.external_pose), options_);
  used_external = match.used_external;
  return match.tracked;
}

bool Tracker::trackReferenceKeyFrame(map::Frame& frame) {
  if (!reference_kf_ || reference_kf_->isBad()) return false;
  return tracking::trackReferenceKeyFrame(frame, *reference_kf_, last_frame_.T_cw, options_);
}

bool Tracker::recoverNearLastPose(map::Frame& frame, const std::optional<core::SE3>& external_T_cw) {
  if (local_map_.points().empty()) return false;
  return recoverNearPredictions(frame, recoveryPredictions(*last_tracked_, frame.id, external_T_cw), local_map_,
                                options_);
}

void Tracker::markRelocalized(map::FrameId frame, FrameOutcome& outcome) {
  last_relocalization_ = frame;
  outcome.relocalized = true;
}

bool Tracker::relocalizedWithin(map::FrameId frame, map::FrameId frames) const {
  return last_relocalization_ && frame < *last_relocalization_ + frames;
}

bool Tracker::trackLocalMap(map::Frame& frame, int& inliers) {
  LocalMapSearch search;
  search.radius = relocalizedWithin(frame.id, 2) ? options_.reloc_search_radius : options_.local_search_radius;
  const auto settling = static_cast<map::FrameId>(options_.max_frames_between_keyframes);
  search.min_inliers = relocalizedWithin(frame.id, settling) ? options_.reloc_min_inliers : options_.local_min_inliers;
  const LocalMapRefinement refined = refineWithLocalMap(frame, local_map_, *map_, search, options_);
  if (refined.reference) {
    reference_kf_ = refined.reference;
    frame.reference_kf = refined.reference->id();
  }
  inliers = refined.inliers;
  return refined.tracked;
}

void Tracker::refinePhotometrically(map::Frame& frame) {
  core::Stopwatch watch;
  const PhotometricRefinementStats s = photometric_->refine(frame, reference_kf_->id(), reference_kf_->T_cw());
  recordTime("track.photometric", watch);
  photometric_link_.reset();
  if (s.accepted) {
    photometric_link_ =
        FramePoseLink{frame.id, {reference_kf_->id(), frame.T_cw * reference_kf_->T_cw().inverse(), s.information}};
  }
  spdlog::debug("frame {}: photometric refinement {} accepted {}, {} points, sigma {:.2f}", frame.id, s.attempted,
                s.accepted, s.points, s.sigma);
}

bool Tracker::needNewKeyFrame(const map::Frame& frame, int inliers) const {
  if (options_.localization_only) return false;
  std::optional<core::SE3> T_rw;
  if (reference_kf_) T_rw = map_->keyFramePose(reference_kf_->id());
  const KeyFrameEvidence evidence = keyFrameEvidence(frame, inliers);
  return wantsKeyFrame(evidence, frame, T_rw, options_) && mappingTakesKeyFrame(evidence.mapping_idle);
}

KeyFrameEvidence Tracker::keyFrameEvidence(const map::Frame& frame, int inliers) const {
  KeyFrameEvidence e;
  e.frame = frame.id;
  e.last_keyframe_frame = last_keyframe_frame_;
  e.last_relocalization = last_relocalization_;
  e.inliers = inliers;
  e.keyframes_in_map = static_cast<int>(map_->numKeyFrames());
  const int min_obs = e.keyframes_in_map <= 2 ? 2 : 3;
  e.reference_tracked = reference_kf_ ? reference_kf_->trackedMapPoints(min_obs) : 0;
  e.close = countClosePoints(frame);
  e.mapping_idle = sink_ ? sink_->isIdle() : true;
  return e;
}

bool Tracker::mappingTakesKeyFrame(bool idle) const {
  if (idle || !sink_) return true;
  sink_->interruptBundleAdjustment();
  return sink_->queuedKeyFrames() < 3;
}

void Tracker::updateMotion(const map::Frame& frame, const FrameOutcome& outcome) {
  state_ = outcome.tracked ? TrackingState::kOk : TrackingState::kLost;
  velocity_ = nextVelocity(velocity_,
                           {outcome.tracked, outcome.relocalized, last_frame_tracked_, frame.T_cw, last_frame_.T_cw});
}

void Tracker::createNewKeyFrame(map::Frame& frame) {
  core::Stopwatch watch;
  KeyFrameInsertion insertion;
  insertion.new_points_min = options_.new_points_min;
  insertion.photometric = photometric_ ? &*photometric_ : nullptr;
  if (photometric_link_ && photometric_link_->frame == frame.id) insertion.photometric_link = &photometric_link_->link;
  NewKeyFrame created = insertKeyFrame(*map_, frame, insertion);
  reference_kf_ = created.kf;
  frame.reference_kf = created.kf->id();
  last_keyframe_frame_ = frame.id;
  if (sink_) sink_->insertKeyFrame(created.kf, std::move(created.new_points));
  recordTime("track.new_keyframe", watch);
}

TrackResult Tracker::commit(map::Frame frame, const FrameOutcome& outcome) {
  ReferenceAnchoring anchoring;
  anchoring.tracked = outcome.tracked;
  anchoring.own_keyframe = outcome.new_keyframe;
  if (outcome.tracked) anchoring.reference_kf = reference_kf_->id();
  anchoring.last_reference_kf = last_frame_.reference_kf;
  anchoring.last_T_cr = last_T_cr_;
  {
    std::shared_lock lock(map_->mutex());
    last_T_cr_ = anchorToReference(frame, anchoring, *map_);
  }
  TrackResult result;
  result.state = state_;
  result.relocalized = outcome.relocalized;
  result.new_keyframe = outcome.new_keyframe;
  result.used_external_pose = outcome.used_external_pose;
  result.inliers = outcome.inliers;
  result.T_cw = frame.T_cw;
  result.reference_kf = frame.reference_kf;
  result.T_cr = last_T_cr_;
  spdlog::debug("frame {}: {} inliers {} ref kf {}{}{}", frame.id, toString(state_), outcome.inliers,
                frame.reference_kf, result.new_keyframe ? " new keyframe" : "",
                result.relocalized ? " relocalised" : "");
  if (outcome.tracked) last_tracked_ = LastTrackedPose{frame.T_cw, frame.id, velocity_};
  last_frame_ = std::move(frame);
  last_frame_tracked_ = outcome.tracked;
  return result;
}

void Tracker::recordTime(const char* stage, core::Stopwatch& watch) const {
  if (times_) times_->add(stage, watch.elapsedMs());
  watch.restart();
}

}  // namespace amos::tracking
