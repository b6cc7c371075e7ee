#pragma once
// Per-frame RGB-D camera tracking (ORB-SLAM2's Tracking, RGB-D mode), as a sequence of named steps, each in its
// own file and tested alone (stella_vslam's tracking module has the same shape):
//   predict            pose_prediction.h     constant-velocity and external poses; the recovery's extrapolation
//   match              frame_matching.h      a first pose from the last frame (motion model) or the reference
//                                            keyframe; when lost, recovery.h near the last pose, then relocalizer.h
//   refine             local_map_refinement.h (local_map.h) the pose against the local map; then
//                      photometric_refiner.h against the reference keyframe's pixels
//   decide keyframe    keyframe_decision.h   the keyframe rules
//   commit             frame_commit.h, keyframe_insertion.h  velocity, matches kept, the pose relative to the
//                                            reference keyframe; the new keyframe and its points
// The map is initialised from the first frame with enough depth.
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
#include "amos/map/frame.h"
#include "amos/map/map.h"
#include "amos/tracking/keyframe_decision.h"
#include "amos/tracking/keyframe_sink.h"
#include "amos/tracking/local_map.h"
#include "amos/tracking/photometric_refiner.h"
#include "amos/tracking/pose_prediction.h"
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
  // What the steps found for one frame, handed from step to step.
  struct FrameOutcome {
    bool tracked = false;
    bool relocalized = false;  // by the relocaliser or the recovery near the last pose
    bool used_external_pose = false;
    bool new_keyframe = false;
    int inliers = 0;
  };

  // Checks the frame and sets up what its first use needs.
  void prepare(map::Frame& frame);
  // Before the first frame: true when the map is empty (the frame is to initialise it); a loaded map makes
  // tracking lost, to localise in it (cold start).
  bool startsNewMap();
  TrackResult initialize(map::Frame& frame);

  // Predict and match: from the last frame while tracking is ok, else recovery or relocalisation.
  FrameOutcome estimateInitialPose(map::Frame& frame, const std::optional<core::SE3>& external_T_cw);
  FrameOutcome followLastFrame(map::Frame& frame, const std::optional<core::SE3>& external_T_cw);
  FrameOutcome relocalize(map::Frame& frame, const std::optional<core::SE3>& external_T_cw);
  // The last frame brought up to date: fused points followed, pose from its (maybe moved) reference keyframe,
  // temporary points from its depth.
  void refreshLastFrame();
  bool trackWithMotionModel(map::Frame& frame, const std::optional<core::SE3>& external, bool& used_external);
  bool trackReferenceKeyFrame(map::Frame& frame);
  // Recently lost: matches the last local map around the external pose, the last tracked pose carried on by its
  // velocity, and the last tracked pose (see recovery_frames).
  bool recoverNearLastPose(map::Frame& frame, const std::optional<core::SE3>& external_T_cw);
  void markRelocalized(map::FrameId frame, FrameOutcome& outcome);
  bool relocalizedWithin(map::FrameId frame, map::FrameId frames) const;

  // Refine.
  bool trackLocalMap(map::Frame& frame, int& inliers);
  void refinePhotometrically(map::Frame& frame);

  // Decide keyframe. Called with the map's shared lock held.
  bool needNewKeyFrame(const map::Frame& frame, int inliers) const;
  KeyFrameEvidence keyFrameEvidence(const map::Frame& frame, int inliers) const;
  // Local mapping takes a keyframe now: it is idle (as the keyframe rules saw it), or its bundle adjustment is
  // interrupted and its queue is short.
  bool mappingTakesKeyFrame(bool idle) const;

  // Commit.
  void updateMotion(const map::Frame& frame, const FrameOutcome& outcome);
  void createNewKeyFrame(map::Frame& frame);
  TrackResult commit(map::Frame frame, const FrameOutcome& outcome);

  void recordTime(const char* stage, core::Stopwatch& watch) const;

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
  std::optional<map::FrameId> last_relocalization_;  // the last frame relocalised or recovered
  std::optional<LastTrackedPose> last_tracked_;      // the last frame that was tracked (kept while lost)
  LocalMap local_map_;
  std::vector<map::MapPointPtr> temporary_points_;  // visual-odometry points of the last frame (not in the map)
};

}  // namespace amos::tracking
