#pragma once
// Per-frame RGB-D camera tracking (ORB-SLAM2's Tracking, RGB-D mode): map initialisation from the first frame
// with enough depth, constant-velocity tracking with projection matching, fall-back to the reference keyframe,
// tracking of the local map, keyframe decision, relocalisation when lost.
//
// Hooks for the dynamic front end (paper Sec. III): keypoints inside the frame's dynamic mask are removed when the
// frame is built (map::buildFrameFeatures) and map points that project into the mask are counted
// (MapPoint::dynamicHits); an externally supplied initial pose can replace or compete with the constant-velocity
// prediction; state(), velocity(), referenceKeyFrameId() and referenceKeyFrameView() expose what the front end
// needs, which the SLAM system hands it as values (system::TrackingView).
//
// A tracker given a map that already has keyframes (a loaded map) starts lost: the first frame is relocalised in
// that map (cold start) instead of initialising a new one.
//
// Threading: a Tracker is used from one thread (the caller's). It reads the map under a shared lock and takes
// the exclusive lock only to insert a keyframe.
#include <memory>
#include <optional>
#include <vector>

#include "amos/core/pose.h"
#include "amos/core/stage_timer.h"
#include "amos/geometry/pose_optimizer.h"
#include "amos/map/frame.h"
#include "amos/map/map.h"
#include "amos/match/matching_options.h"
#include "amos/tracking/keyframe_sink.h"
#include "amos/tracking/matching.h"
#include "amos/tracking/photometric_refiner.h"
#include "amos/tracking/relocalizer.h"
#include "amos/tracking/tracker_options.h"

namespace amos::tracking {

enum class TrackingState { kNotInitialized, kOk, kLost };
const char* toString(TrackingState state);

struct TrackResult {
  TrackingState state = TrackingState::kNotInitialized;
  bool initialized_map = false;
  bool relocalized = false;
  bool new_keyframe = false;
  bool used_external_pose = false;
  int inliers = 0;
  core::SE3 T_cw = core::SE3::Identity();
  // Pose relative to the reference keyframe (T_cr = T_cw * T_wr), so later map corrections reach the trajectory.
  map::KeyFrameId reference_kf = map::kNoKeyFrame;
  core::SE3 T_cr = core::SE3::Identity();
};

// The reference keyframe as the dynamic front end sees it (paper's model 1: reference keyframe features).
struct ReferenceKeyFrameView {
  map::KeyFrameId id = map::kNoKeyFrame;
  core::SE3 T_cw = core::SE3::Identity();
  std::vector<cv::KeyPoint> keypoints;         // undistorted
  std::vector<Eigen::Vector3d> points_w;       // world position of the keypoint's map point ...
  std::vector<bool> has_point;                 // ... when it has one
};

class Tracker {
 public:
  // places: the keyframes' bag-of-words database for relocalisation (null: thumbnails, see relocalizer.h).
  Tracker(const TrackerOptions& options, std::shared_ptr<map::Map> map, KeyFrameSink* sink,
          core::StageTimes* times = nullptr, std::shared_ptr<const place::KeyFrameDatabase> places = nullptr);

  // Tracks one frame (built with map::buildFrameFeatures / makeFrame). external_T_cw: optional initial pose from
  // outside (e.g. the dynamic front end), used according to options.external_pose.
  TrackResult track(map::Frame frame, const std::optional<core::SE3>& external_T_cw = std::nullopt);

  TrackingState state() const { return state_; }
  // Pose of the last tracked frame, the constant-velocity motion (T_cur_last), if known.
  std::optional<core::SE3> lastPose() const;
  std::optional<core::SE3> velocity() const { return velocity_; }
  // The reference keyframe's id (map::kNoKeyFrame before the map exists), and the keyframe as the front end sees it.
  map::KeyFrameId referenceKeyFrameId() const { return reference_kf_ ? reference_kf_->id() : map::kNoKeyFrame; }
  ReferenceKeyFrameView referenceKeyFrameView() const;
  const map::Frame& lastFrame() const { return last_frame_; }

 private:
  TrackResult initialize(map::Frame& frame);
  bool trackWithMotionModel(map::Frame& frame, const std::optional<core::SE3>& external, bool& used_external);
  bool trackReferenceKeyFrame(map::Frame& frame);
  bool trackLocalMap(map::Frame& frame, int& inliers);
  // Recently lost: matches the last local map around the external pose, the last tracked pose carried on by its
  // velocity, and the last tracked pose (see recovery_frames).
  bool recoverNearLastPose(map::Frame& frame, const std::optional<core::SE3>& external_T_cw);
  void updateLastFrame();
  void updateLocalMap(map::Frame& frame);
  void searchLocalPoints(map::Frame& frame);
  // Drops outlier matches after pose optimisation; returns matches to points that are in the map.
  int discardOutliers(map::Frame& frame) const;
  bool needNewKeyFrame(const map::Frame& frame, int inliers) const;
  // How far the frame's camera is from its reference keyframe's: the turn (degrees) and the baseline as a share of
  // the frame's median keypoint depth; nullopt without a reference keyframe or keypoint depths. Called with the
  // map's shared lock held.
  struct ViewChange {
    double rotation_deg = 0;
    double baseline_share = 0;
  };
  std::optional<ViewChange> viewChangeFromReference(const map::Frame& frame) const;
  // Whether movers (the frame's dynamic mask) cover Tracking.keyFrameMoverShare of the image and the camera, `view`
  // away from its reference keyframe (viewChangeFromReference), is within Tracking.keyFrameMinRotation /
  // keyFrameMinBaseline of it.
  bool stillBehindMovers(const map::Frame& frame, const std::optional<ViewChange>& view) const;
  void createNewKeyFrame(map::Frame& frame);

  TrackerOptions options_;
  std::shared_ptr<map::Map> map_;
  KeyFrameSink* sink_;
  core::StageTimes* times_;
  Relocalizer relocalizer_;

  TrackingState state_ = TrackingState::kNotInitialized;
  map::Frame last_frame_;
  bool last_frame_tracked_ = false;
  core::SE3 last_T_cr_ = core::SE3::Identity();  // last frame relative to its reference keyframe
  std::optional<core::SE3> velocity_;
  map::KeyFramePtr reference_kf_;
  std::optional<PhotometricRefiner> photometric_;  // when options_.photometric
  // A frame's pose relative to its reference keyframe as the pixels alone measured it; a keyframe made from that
  // frame carries it into bundle adjustment (map::PoseLink).
  struct FramePoseLink {
    map::FrameId frame = 0;
    map::PoseLink link;
  };
  std::optional<FramePoseLink> photometric_link_;
  map::FrameId last_keyframe_frame_ = 0;
  map::FrameId last_reloc_frame_ = 0;
  std::optional<core::SE3> last_tracked_T_cw_;  // pose of the last frame that was tracked (kept while lost)
  map::FrameId last_tracked_frame_ = 0;
  std::optional<core::SE3> last_tracked_velocity_;  // velocity at that frame (for the recovery's extrapolation)
  bool relocalized_once_ = false;
  std::vector<map::KeyFramePtr> local_keyframes_;
  std::vector<map::MapPointPtr> local_points_;
  std::vector<map::MapPointPtr> temporary_points_;  // visual-odometry points of the last frame (not in the map)
};

}  // namespace amos::tracking
