#pragma once
// Step "decide keyframe": whether a tracked frame should become a keyframe. ORB-SLAM2's RGB-D rules (the frame
// tracks too few of its reference keyframe's points, or too few close points, and time has passed or mapping is
// idle) with this project's two view rules (a keyframe once the view has moved on even while mapping is busy; none
// while movers hide part of a view the reference keyframe already holds); see TrackerOptions for the settings and
// their reasons. The rules are pure functions of the evidence gathered from the frame and the map, each tested alone.
#include <optional>

#include <opencv2/core.hpp>

#include "amos/core/pose.h"
#include "amos/map/frame.h"
#include "amos/map/ids.h"
#include "amos/tracking/tracker_options.h"

namespace amos::tracking {

// The frame's keypoints with depth nearer than Sensor::closeDepth(): tracked (an inlier match) or not.
struct ClosePoints {
  int tracked = 0;
  int untracked = 0;
};
ClosePoints countClosePoints(const map::Frame& frame);

// How far the frame's camera is from its reference keyframe's: the turn (degrees) and the baseline as a share of
// the frame's median keypoint depth. nullopt when no keypoint has depth.
struct ViewChange {
  double rotation_deg = 0;
  double baseline_share = 0;
};
std::optional<ViewChange> viewChange(const map::Frame& frame, const core::SE3& T_rw);

// What the rules read besides the frame itself.
struct KeyFrameEvidence {
  map::FrameId frame = 0;                           // the frame's id
  map::FrameId last_keyframe_frame = 0;             // the frame the last keyframe was made from
  std::optional<map::FrameId> last_relocalization;  // the last frame relocalised (or recovered), if any
  int inliers = 0;                                  // the frame's inlier matches to map points
  int reference_tracked = 0;                        // the reference keyframe's points seen by 2 keyframes (3 once
                                                    // the map has more than 2)
  int keyframes_in_map = 0;
  ClosePoints close;
  bool mapping_idle = true;
};

// The frames after a relocalisation make no keyframe (unless the map is still small).
bool settlingAfterRelocalisation(const KeyFrameEvidence& e, const TrackerOptions& o);
// Many close points the map does not have: the frame could add near structure.
bool lacksClosePoints(const KeyFrameEvidence& e, const TrackerOptions& o);
// The frame tracks less than Tracking.keyFrameRefRatio of its reference's points (0.4 while the map has one
// keyframe), or lacks close points, and still tracks more than 15 (ORB-SLAM2's c2).
bool losingReferencePoints(const KeyFrameEvidence& e, const TrackerOptions& o);
// The view has moved on (Tracking.keyFrameViewRotation / keyFrameViewBaseline).
bool viewMovedOn(const std::optional<ViewChange>& view, const TrackerOptions& o);
// Time or need allows a keyframe: Tracking.maxFrames since the last one, minFrames with mapping idle, a quarter of
// the reference's points or close points lost (ORB-SLAM2's c1a-c1c), or the view moved on.
bool keyFrameDue(const KeyFrameEvidence& e, const std::optional<ViewChange>& view, const TrackerOptions& o);
// Tracking is sound: a quarter of the reference's points and Tracking.closeTrackedMax map points.
bool trackingSound(const KeyFrameEvidence& e, const TrackerOptions& o);
// Movers (the dynamic mask) cover Tracking.keyFrameMoverShare of the image while the camera is within
// keyFrameMinRotation / keyFrameMinBaseline of its reference keyframe.
bool stillBehindMovers(const cv::Mat& dynamic_mask, const std::optional<ViewChange>& view, const TrackerOptions& o);

// The decision (before asking local mapping to take the keyframe). T_rw: the reference keyframe's pose (nullopt:
// none); the view change is measured only when the cheaper rules leave the decision open.
bool wantsKeyFrame(const KeyFrameEvidence& e, const map::Frame& frame, const std::optional<core::SE3>& T_rw,
                   const TrackerOptions& o);

}  // namespace amos::tracking
