#include "amos/tracking/tracker.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <unordered_set>
#include <opencv2/core.hpp>

#include "amos/core/error.h"
#include "amos/match/brute_force_search.h"
#include "amos/match/pose_from_matches.h"
#include "amos/tracking/dynamic_evidence.h"

namespace amos::tracking {

namespace {
// (depth, keypoint index) of the keypoints with valid depth, closest first: both the temporary points of the
// motion model and a new keyframe's depth points are taken in this order.
std::vector<std::pair<float, int>> keypointsByDepth(const map::FrameFeatures& f) {
  std::vector<std::pair<float, int>> by_depth;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] > 0) by_depth.emplace_back(f.depth[i], static_cast<int>(i));
  }
  std::sort(by_depth.begin(), by_depth.end());
  return by_depth;
}
}  // namespace

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

TrackResult Tracker::track(map::Frame frame, const std::optional<core::SE3>& external_T_cw) {
  core::require(frame.features && frame.sensor, "Tracker::track: frame without features");
  if (options_.photometric && !photometric_) photometric_.emplace(frame.sensor->camera(), options_.photometric_options);
  if (frame.map_points.size() != frame.size()) frame.resetMatches();
  TrackResult result;
  if (state_ == TrackingState::kNotInitialized) {
    bool has_map = false;
    {
      std::shared_lock lock(map_->mutex());
      has_map = map_->numKeyFrames() > 0;
    }
    // A loaded map: localise in it (cold start) rather than start a new one beside it.
    if (has_map) {
      state_ = TrackingState::kLost;
    } else {
      core::require(!options_.localization_only, "Tracker: localization mode needs a loaded map (--load-map)");
      return initialize(frame);
    }
  }

  bool ok = false, need_keyframe = false;
  int inliers = 0;
  {
    std::shared_lock lock(map_->mutex());
    core::Stopwatch watch;
    if (state_ == TrackingState::kOk) {
      // Points fused by local mapping since the last frame: follow them to the survivor.
      for (auto& p : last_frame_.map_points) {
        if (!p) continue;
        if (const auto replacement = p->replacedBy()) p = replacement;
      }
      updateLastFrame();
      const bool recent_reloc = relocalized_once_ && frame.id < last_reloc_frame_ + 2;
      if ((velocity_ || external_T_cw) && !recent_reloc) {
        ok = trackWithMotionModel(frame, external_T_cw, result.used_external_pose);
        if (!ok) ok = trackReferenceKeyFrame(frame);
      } else {
        ok = trackReferenceKeyFrame(frame);
        // Right after a relocalisation the reference keyframe may share too few descriptors with the frame;
        // the relocalised pose itself (no velocity yet) is still a good prediction for a projection search.
        if (!ok) ok = trackWithMotionModel(frame, external_T_cw, result.used_external_pose);
      }
      // Both failed (in crowds: the narrow window's matches mostly on temporary points, too few in the map): the
      // recovery's wide window and PnP RANSAC over the local map, on this frame rather than after it is lost.
      if (!ok && options_.recovery_frames > 0 && last_tracked_T_cw_ && recoverNearLastPose(frame, external_T_cw)) {
        ok = true;
        last_reloc_frame_ = frame.id;  // its local map tracking must then meet relocMinInliers
        relocalized_once_ = true;
        result.relocalized = true;
        spdlog::debug("frame {}: recovered in the same frame near the predicted pose", frame.id);
      }
    } else {
      const bool recently_lost = options_.recovery_frames > 0 && last_tracked_T_cw_ &&
                                 frame.id <= last_tracked_frame_ + static_cast<map::FrameId>(options_.recovery_frames);
      if (recently_lost && recoverNearLastPose(frame, external_T_cw)) {
        ok = true;
        spdlog::debug("frame {}: recovered near the last tracked pose", frame.id);
      } else {
        const map::KeyFramePtr kf = relocalizer_.relocalize(frame, *map_);
        ok = kf != nullptr;
        if (ok) {
          reference_kf_ = kf;
          spdlog::debug("frame {}: relocalised against keyframe {}", frame.id, kf->id());
        }
      }
      if (ok) {
        last_reloc_frame_ = frame.id;
        relocalized_once_ = true;
        result.relocalized = true;
      }
    }
    if (times_) times_->add("track.initial_pose", watch.elapsedMs());
    watch.restart();
    if (ok) ok = trackLocalMap(frame, inliers);
    if (times_) times_->add("track.local_map", watch.elapsedMs());
    if (ok && photometric_) {
      watch.restart();
      const PhotometricRefinementStats s = photometric_->refine(frame, reference_kf_->id(), reference_kf_->T_cw());
      if (times_) times_->add("track.photometric", watch.elapsedMs());
      photometric_link_.reset();
      if (s.accepted) {
        photometric_link_ = FramePoseLink{
            frame.id, {reference_kf_->id(), frame.T_cw * reference_kf_->T_cw().inverse(), s.information}};
      }
      spdlog::debug("frame {}: photometric refinement {} accepted {}, {} points, sigma {:.2f}", frame.id, s.attempted,
                    s.accepted, s.points, s.sigma);
    }
    state_ = ok ? TrackingState::kOk : TrackingState::kLost;
    if (ok && last_frame_tracked_ && !result.relocalized) {
      velocity_ = map::orthonormalized(frame.T_cw * last_frame_.T_cw.inverse());
    } else if (!ok || result.relocalized) {
      velocity_.reset();
    }
    // Visual-odometry matches (temporary points) do not survive the frame.
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const auto& p = frame.map_points[i];
      if (p && p->numObservations() < 1) {
        frame.map_points[i].reset();
        frame.outlier[i] = false;
      }
    }
    temporary_points_.clear();
    if (ok) need_keyframe = needNewKeyFrame(frame, inliers);
  }
  // Outliers take no part in the keyframe nor in the next frame's motion-model search.
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.map_points[i] && frame.outlier[i]) frame.map_points[i].reset();
    frame.outlier[i] = false;
  }
  if (need_keyframe) {
    core::Stopwatch watch;
    createNewKeyFrame(frame);
    result.new_keyframe = true;
    if (times_) times_->add("track.new_keyframe", watch.elapsedMs());
  }
  result.state = state_;
  result.inliers = inliers;
  {
    std::shared_lock lock(map_->mutex());
    if (ok && result.new_keyframe) {
      // The frame is its own keyframe: it follows every later correction of that keyframe (in lock-step mode
      // local mapping has already adjusted it by now).
      frame.reference_kf = reference_kf_->id();
      last_T_cr_ = core::SE3::Identity();
    } else if (ok) {
      frame.reference_kf = reference_kf_->id();
      last_T_cr_ = map::orthonormalized(frame.T_cw * map_->keyFramePose(frame.reference_kf).inverse());
    } else {
      // Lost: keep the last relative pose (as ORB-SLAM2 does), so the trajectory still has a line per frame;
      // none before the first frame localised in a loaded map.
      frame.reference_kf = last_frame_.reference_kf;
      if (frame.reference_kf != map::kNoKeyFrame) frame.T_cw = last_T_cr_ * map_->keyFramePose(frame.reference_kf);
    }
  }
  result.reference_kf = frame.reference_kf;
  result.T_cr = last_T_cr_;
  spdlog::debug("frame {}: {} inliers {} ref kf {}{}{}", frame.id, toString(state_), inliers, frame.reference_kf,
                result.new_keyframe ? " new keyframe" : "", result.relocalized ? " relocalised" : "");
  result.T_cw = frame.T_cw;
  if (ok) {
    last_tracked_T_cw_ = frame.T_cw;
    last_tracked_frame_ = frame.id;
    last_tracked_velocity_ = velocity_;
  }
  last_frame_ = std::move(frame);
  last_frame_tracked_ = ok;
  return result;
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
  std::vector<map::MapPointPtr> new_points;
  map::KeyFramePtr kf;
  {
    std::unique_lock lock(map_->mutex());
    kf = std::make_shared<map::KeyFrame>(map_->newKeyFrameId(), frame);
    map_->addKeyFrame(kf);
    if (photometric_) photometric_->addKeyFrame(kf->id(), frame);
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (!f.hasDepth(static_cast<int>(i))) continue;
      auto p = map_->createMapPoint(frame.unproject(static_cast<int>(i)), kf, static_cast<int>(i), frame.id);
      frame.map_points[i] = p;
      new_points.push_back(p);
    }
  }
  spdlog::debug("map initialised from frame {} with {} points", frame.id, new_points.size());
  if (sink_) sink_->insertKeyFrame(kf, std::move(new_points));
  reference_kf_ = kf;
  frame.reference_kf = kf->id();
  last_keyframe_frame_ = frame.id;
  local_keyframes_ = {kf};
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

void Tracker::updateLastFrame() {
  map::Frame& last = last_frame_;
  // The reference keyframe may have moved (bundle adjustment) since the last frame was tracked.
  if (last.reference_kf != map::kNoKeyFrame && map_->knowsKeyFrame(last.reference_kf)) {
    last.setPose(last_T_cr_ * map_->keyFramePose(last.reference_kf));
  }
  if (last_keyframe_frame_ == last.id || !last_frame_tracked_) return;
  // RGB-D: temporary points from the last frame's depth give the motion-model search more to match
  // (closest first; all close ones, at least vo_points_min).
  const map::FrameFeatures& f = *last.features;
  const auto by_depth = keypointsByDepth(f);
  int n = 0;
  for (const auto& [z, i] : by_depth) {
    const auto& p = last.map_points[i];
    if (!p || p->numObservations() < 1) {
      auto temp = std::make_shared<map::MapPoint>(map::kNoMapPoint, last.unproject(i), map::kNoKeyFrame, last.id);
      temp->setDescriptor(f.descriptors.row(i));
      last.map_points[i] = temp;
      last.outlier[i] = false;
      temporary_points_.push_back(std::move(temp));
    }
    ++n;
    if (z > last.sensor->closeDepth() && n > options_.vo_points_min) break;
  }
}

int Tracker::discardOutliers(map::Frame& frame) const {
  int in_map = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    auto& p = frame.map_points[i];
    if (!p) continue;
    if (frame.outlier[i]) {
      p.reset();
      frame.outlier[i] = false;
    } else if (p->numObservations() > 0) {
      ++in_map;
    }
  }
  return in_map;
}

bool Tracker::trackWithMotionModel(map::Frame& frame, const std::optional<core::SE3>& external,
                                   bool& used_external) {
  std::vector<std::pair<core::SE3, bool>> predictions;  // (T_cw, is external)
  if (external) predictions.emplace_back(*external, true);
  if (velocity_ && !(external && options_.external_pose == ExternalPosePolicy::kReplace)) {
    predictions.emplace_back(*velocity_ * last_frame_.T_cw, false);
  }
  if (predictions.empty() && last_frame_tracked_) predictions.emplace_back(last_frame_.T_cw, false);  // no velocity yet
  const double th = options_.motion_search_radius;
  int best_n = -1;
  std::vector<map::MapPointPtr> best_matches;
  core::SE3 best_pose = core::SE3::Identity();
  for (const auto& [T, is_external] : predictions) {
    frame.resetMatches();
    frame.setPose(T);
    int n = searchLastFrame(frame, last_frame_, th, options_.matching);
    if (n < options_.motion_min_matches) {
      frame.resetMatches();
      n = searchLastFrame(frame, last_frame_, 2 * th, options_.matching);
    }
    if (n > best_n) {
      best_n = n;
      best_matches = frame.map_points;
      best_pose = T;
      used_external = is_external;
    }
  }
  spdlog::debug("frame {}: motion model {} matches", frame.id, best_n);
  if (best_n < options_.motion_min_matches) return false;
  frame.map_points = std::move(best_matches);
  frame.outlier.assign(frame.size(), false);
  frame.setPose(best_pose);
  const int inl = match::optimizeFramePose(frame, options_.pose);
  const int in_map = discardOutliers(frame);
  spdlog::debug("frame {}: motion model inliers {} (in map {}) prediction off by {:.4f} m {:.3f} deg; velocity {:.4f} m",
                frame.id, inl, in_map, core::translationNorm(best_pose * frame.T_cw.inverse()),
                core::rotationAngle(best_pose * frame.T_cw.inverse()) * 57.3, velocity_ ? core::translationNorm(*velocity_) : -1.0);
  return in_map >= options_.min_map_matches;
}

bool Tracker::trackReferenceKeyFrame(map::Frame& frame) {
  if (!reference_kf_ || reference_kf_->isBad()) return false;
  int n = 0;
  auto matches = match::matchFrameToKeyFrame(frame, *reference_kf_, options_.matching.brute_force_ratio,
                                             options_.matching, &n);
  spdlog::debug("frame {}: reference keyframe {} matches", frame.id, n);
  if (n < options_.reference_min_matches) return false;
  frame.map_points = std::move(matches);
  frame.outlier.assign(frame.size(), false);
  frame.setPose(last_frame_.T_cw);
  match::optimizeFramePose(frame, options_.pose);
  return discardOutliers(frame) >= options_.min_map_matches;
}

void Tracker::updateLocalMap(map::Frame& frame) {
  // Local keyframes: those sharing points with the frame, plus a neighbour, a child and the parent of each.
  std::map<map::KeyFrameId, int> counts;
  for (auto& p : frame.map_points) {
    if (!p) continue;
    if (p->isBad()) {
      p.reset();
      continue;
    }
    for (const auto& [kf_id, index] : p->observations()) ++counts[kf_id];
  }
  local_keyframes_.clear();
  std::unordered_set<map::KeyFrameId> included;
  map::KeyFramePtr best;
  int best_count = 0;
  for (const auto& [kf_id, c] : counts) {
    map::KeyFramePtr kf = map_->keyFrame(kf_id);
    if (!kf || kf->isBad()) continue;
    local_keyframes_.push_back(kf);
    included.insert(kf_id);
    if (c > best_count) {
      best_count = c;
      best = kf;
    }
  }
  const std::size_t direct = local_keyframes_.size();
  auto add = [&](map::KeyFrameId id) {
    if (included.count(id)) return false;
    map::KeyFramePtr kf = map_->keyFrame(id);
    if (!kf || kf->isBad()) return false;
    local_keyframes_.push_back(kf);
    included.insert(id);
    return true;
  };
  for (std::size_t k = 0; k < direct; ++k) {
    if (local_keyframes_.size() > static_cast<std::size_t>(options_.max_local_keyframes)) break;
    const map::KeyFramePtr kf = local_keyframes_[k];
    for (const map::KeyFrameId n : kf->bestCovisibles(10)) {
      if (add(n)) break;
    }
    for (const map::KeyFrameId c : kf->children()) {
      if (add(c)) break;
    }
    if (kf->parent() != map::kNoKeyFrame) add(kf->parent());
  }
  if (best) {
    reference_kf_ = best;
    frame.reference_kf = best->id();
  }
  local_points_.clear();
  std::unordered_set<const map::MapPoint*> seen;
  for (const auto& kf : local_keyframes_) {
    for (const auto& p : kf->mapPoints()) {
      if (p && !p->isBad() && seen.insert(p.get()).second) local_points_.push_back(p);
    }
  }
}

void Tracker::searchLocalPoints(map::Frame& frame) {
  std::unordered_set<const map::MapPoint*> in_frame;
  for (auto& p : frame.map_points) {
    if (!p) continue;
    if (p->isBad()) {
      p.reset();
      continue;
    }
    p->increaseVisible();
    in_frame.insert(p.get());
  }
  const bool masked = !frame.dynamic_mask.empty();
  std::vector<ProjectedPoint> candidates;
  candidates.reserve(local_points_.size());
  for (const auto& p : local_points_) {
    if (in_frame.count(p.get())) continue;
    ProjectedPoint pp;
    if (!projectIntoFrame(frame, p, 0.5, pp)) continue;
    p->increaseVisible();
    if (masked) {
      // Evidence for culling points on movers (Sec. III-C). The mask and depth are in raw image coordinates;
      // the undistorted projection is within a few pixels of it, which is enough for a count.
      const MaskEvidence evidence = maskEvidence(frame.dynamic_mask, frame.depth_image, pp.u, pp.v, pp.z);
      if (evidence != MaskEvidence::kNone) p->increaseMaskedViews();
      if (evidence == MaskEvidence::kDynamic) p->increaseDynamicHits();
    }
    candidates.push_back(std::move(pp));
  }
  if (candidates.empty()) return;
  const bool recent_reloc = relocalized_once_ && frame.id < last_reloc_frame_ + 2;
  const double th = recent_reloc ? options_.reloc_search_radius : options_.local_search_radius;
  const int found = tracking::searchLocalPoints(frame, candidates, th, options_.matching);
  spdlog::debug("frame {}: local map {} kfs {} points, {} in view, {} new matches", frame.id, local_keyframes_.size(),
                local_points_.size(), candidates.size(), found);
}

bool Tracker::recoverNearLastPose(map::Frame& frame, const std::optional<core::SE3>& external_T_cw) {
  if (local_points_.empty()) return false;
  std::vector<core::SE3> predictions;
  if (external_T_cw) predictions.push_back(*external_T_cw);
  // A camera that kept moving while the view was covered is nearer where its last velocity takes it than where
  // it was (ORB-SLAM3 predicts the same way while recently lost, with an IMU); one that stopped is at the last pose.
  if (last_tracked_velocity_ && frame.id > last_tracked_frame_) {
    core::SE3 T = *last_tracked_T_cw_;
    for (map::FrameId k = last_tracked_frame_; k < frame.id; ++k) T = *last_tracked_velocity_ * T;
    predictions.push_back(map::orthonormalized(T));
  }
  predictions.push_back(*last_tracked_T_cw_);
  for (const core::SE3& T : predictions) {
    frame.resetMatches();
    frame.setPose(T);
    std::vector<ProjectedPoint> candidates;
    candidates.reserve(local_points_.size());
    for (const auto& p : local_points_) {
      ProjectedPoint pp;
      if (p && !p->isBad() && projectIntoFrame(frame, p, 0.5, pp)) candidates.push_back(std::move(pp));
    }
    const int found = tracking::searchLocalPoints(frame, candidates, options_.recovery_search_radius, options_.matching);
    spdlog::debug("frame {}: recovery search: {} of {} local points in view matched", frame.id, found, candidates.size());
    if (found < options_.reloc_min_inliers) continue;
    // The wide window lets wrong matches in, and the prediction may be degrees off: PnP RANSAC on the matches
    // (as the relocaliser does) rather than a pose optimisation started at the prediction.
    const std::vector<map::MapPointPtr> matches = frame.map_points;
    const int pnp_inliers = match::poseFromMatchesByPnp(frame, matches, options_.relocalization.pnp);
    if (pnp_inliers < options_.reloc_min_inliers) continue;
    const int inliers = match::optimizeFramePoseDroppingOutliers(frame, options_.pose);
    spdlog::debug("frame {}: recovery search {} matches, {} inliers", frame.id, found, inliers);
    if (inliers >= options_.reloc_min_inliers) return true;
  }
  frame.resetMatches();
  return false;
}

bool Tracker::trackLocalMap(map::Frame& frame, int& inliers) {
  updateLocalMap(frame);
  searchLocalPoints(frame);
  match::optimizeFramePose(frame, options_.pose);
  inliers = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto& p = frame.map_points[i];
    if (!p || frame.outlier[i]) continue;
    p->increaseFound();
    if (p->numObservations() > 0) ++inliers;
  }
  const bool after_reloc =
      relocalized_once_ && frame.id < last_reloc_frame_ + static_cast<map::FrameId>(options_.max_frames_between_keyframes);
  if (after_reloc && inliers < options_.reloc_min_inliers) return false;
  return inliers >= options_.local_min_inliers;
}

bool Tracker::needNewKeyFrame(const map::Frame& frame, int inliers) const {
  if (options_.localization_only) return false;
  const int num_kfs = static_cast<int>(map_->numKeyFrames());
  const auto max_frames = static_cast<map::FrameId>(options_.max_frames_between_keyframes);
  if (relocalized_once_ && frame.id < last_reloc_frame_ + max_frames && num_kfs > options_.max_frames_between_keyframes) {
    return false;
  }
  const int min_obs = num_kfs <= 2 ? 2 : 3;
  const int ref_matches = reference_kf_ ? reference_kf_->trackedMapPoints(min_obs) : 0;
  const bool idle = sink_ ? sink_->isIdle() : true;
  // RGB-D: many close points not tracked means the map lacks near structure the frame could add.
  int tracked_close = 0, untracked_close = 0;
  const map::FrameFeatures& f = *frame.features;
  const double close = frame.sensor->closeDepth();
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] > 0 && f.depth[i] < close) {
      if (frame.map_points[i] && !frame.outlier[i]) {
        ++tracked_close;
      } else {
        ++untracked_close;
      }
    }
  }
  const bool need_close = tracked_close < options_.close_tracked_max && untracked_close > options_.close_untracked_min;
  const double ref_ratio = num_kfs < 2 ? 0.4 : options_.keyframe_ref_ratio;
  const bool c1a = frame.id >= last_keyframe_frame_ + max_frames;
  const bool c1b = frame.id >= last_keyframe_frame_ + static_cast<map::FrameId>(options_.min_frames_between_keyframes) && idle;
  const bool c1c = inliers < ref_matches * 0.25 || need_close;
  const bool c2 = (inliers < ref_matches * ref_ratio || need_close) && inliers > 15;
  spdlog::debug("frame {}: keyframe test: inliers {} reference tracked {} (ratio {}) close tracked {} untracked {}{}",
                frame.id, inliers, ref_matches, ref_ratio, tracked_close, untracked_close, idle ? "" : " mapping busy");
  if (!c2) return false;
  // How far the camera is from the reference keyframe's viewpoint, measured once for both view rules.
  const std::optional<ViewChange> view = viewChangeFromReference(frame);
  // The view has moved on from the reference keyframe's, whether or not mapping is idle (keyFrameView*).
  const bool c1d = view && ((options_.keyframe_view_rotation_deg > 0 &&
                             view->rotation_deg >= options_.keyframe_view_rotation_deg) ||
                            (options_.keyframe_view_baseline > 0 &&
                             view->baseline_share >= options_.keyframe_view_baseline));
  if (!(c1a || c1b || c1c || c1d)) return false;
  const bool sound = inliers >= ref_matches * 0.25 && inliers >= options_.close_tracked_max;
  if (sound && stillBehindMovers(frame, view)) {
    spdlog::debug("frame {}: no keyframe: movers hide part of the view, the camera is still at the reference "
                  "keyframe's viewpoint",
                  frame.id);
    return false;
  }
  if (idle) return true;
  if (sink_) {
    sink_->interruptBundleAdjustment();
    return sink_->queuedKeyFrames() < 3;
  }
  return true;
}

std::optional<Tracker::ViewChange> Tracker::viewChangeFromReference(const map::Frame& frame) const {
  if (!reference_kf_) return std::nullopt;
  std::vector<float> depths;
  const map::FrameFeatures& f = *frame.features;
  depths.reserve(f.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.depth[i] > 0) depths.push_back(f.depth[i]);
  if (depths.empty()) return std::nullopt;
  const auto mid = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
  std::nth_element(depths.begin(), mid, depths.end());
  const core::SE3 T_rw = map_->keyFramePose(reference_kf_->id());
  // T_cr = T_cw * T_wr: its rotation is the turn between the two views, its translation (in the camera frame) the
  // baseline between the two camera centres.
  const core::SE3 T_cr = frame.T_cw * T_rw.inverse();
  const double kDegree = 3.14159265358979323846 / 180.0;
  return ViewChange{core::rotationAngle(T_cr) / kDegree, core::translationNorm(T_cr) / static_cast<double>(*mid)};
}

bool Tracker::stillBehindMovers(const map::Frame& frame, const std::optional<ViewChange>& view) const {
  if (!view || options_.keyframe_min_rotation_deg <= 0 || options_.keyframe_min_baseline <= 0 ||
      options_.keyframe_mover_share <= 0 || frame.dynamic_mask.empty())
    return false;
  if (cv::countNonZero(frame.dynamic_mask) < options_.keyframe_mover_share * static_cast<double>(frame.dynamic_mask.total()))
    return false;
  return view->rotation_deg < options_.keyframe_min_rotation_deg &&
         view->baseline_share < options_.keyframe_min_baseline;
}

void Tracker::createNewKeyFrame(map::Frame& frame) {
  std::vector<map::MapPointPtr> new_points;
  map::KeyFramePtr kf;
  {
    std::unique_lock lock(map_->mutex());
    kf = std::make_shared<map::KeyFrame>(map_->newKeyFrameId(), frame);
    map_->addKeyFrame(kf);
    if (photometric_) photometric_->addKeyFrame(kf->id(), frame);
    if (photometric_link_ && photometric_link_->frame == frame.id) kf->setPhotometricLink(photometric_link_->link);
    for (int i = 0; i < kf->size(); ++i) {
      const map::MapPointPtr p = kf->mapPoint(i);
      if (!p) continue;
      if (p->isBad() || p->isObservedBy(kf->id())) {
        kf->clearMapPoint(i);
        frame.map_points[i].reset();
        continue;
      }
      map_->addObservation(p, kf, i);
    }
    // New points from depth, closest first: all close ones, and at least new_points_min.
    const auto by_depth = keypointsByDepth(*frame.features);
    int n = 0;
    for (const auto& [z, i] : by_depth) {
      if (!frame.map_points[i]) {
        auto p = map_->createMapPoint(frame.unproject(i), kf, i, frame.id);
        frame.map_points[i] = p;
        new_points.push_back(std::move(p));
      }
      ++n;
      if (z > frame.sensor->closeDepth() && n > options_.new_points_min) break;
    }
  }
  reference_kf_ = kf;
  frame.reference_kf = kf->id();
  last_keyframe_frame_ = frame.id;
  if (sink_) sink_->insertKeyFrame(kf, std::move(new_points));
}

}  // namespace amos::tracking
