#pragma once
// Tracking's settings (Tracking.*, with Matching.* and Relocalization.*): what every tracking step reads.
#include "amos/geometry/photometric_alignment.h"
#include "amos/geometry/pose_optimizer.h"
#include "amos/match/matching_options.h"
#include "amos/tracking/relocalizer.h"

namespace amos::tracking {

// How an externally supplied initial pose is used (Tracking.externalPose: replace | compete).
enum class ExternalPosePolicy { kReplace, kCompete };

// ORB-SLAM2's RGB-D "close points" keyframe test (100 tracked, 70 untracked) is set for its 1000 features per
// frame: counts of a frame's points, so they scale with the features extracted. Held at 100 / 70 with 2000
// features the test rarely fires: on the Bonn crowd frames tracking 110-160 of their close points while 300-400
// more were not in the map made no keyframe for 55 frames, and the pose slid 5 cm sideways
// (docs/experiments/close-points-scale.md).
inline int closeTrackedMaxFor(int num_features) { return num_features / 10; }
inline int closeUntrackedMinFor(int num_features) { return num_features * 7 / 100; }

struct TrackerOptions {
  int init_min_depth_points = 500;   // Tracking.initMinDepthPoints: keypoints with depth to initialise the map
  double motion_search_radius = 15;  // Tracking.motionSearchRadius: px at level 0 (ORB-SLAM2 RGB-D: 15)
  int motion_min_matches = 20;       // Tracking.motionMinMatches: below this the window is doubled, then fail
  int min_map_matches = 10;          // Tracking.minMapMatches: inliers with map points to accept a frame-to-frame step
  int reference_min_matches = 15;    // Tracking.referenceMinMatches: brute-force matches to try the reference KF
  double local_search_radius = 3;    // Tracking.localSearchRadius (ORB-SLAM2 RGB-D: 3)
  double reloc_search_radius = 5;    // Tracking.relocSearchRadius: local-map window in the frames right after relocalisation
  int local_min_inliers = 30;        // Tracking.localMinInliers
  int reloc_min_inliers = 50;        // Tracking.relocMinInliers: inliers needed in the frames after a relocalisation
  int max_local_keyframes = 80;      // Tracking.maxLocalKeyFrames
  int max_frames_between_keyframes = 30;  // Tracking.maxFrames (ORB-SLAM2: fps)
  int min_frames_between_keyframes = 0;   // Tracking.minFrames
  // Tracking.keyFrameRefRatio: a keyframe when the frame tracks fewer than this share of the reference keyframe's
  // points (with one of the timing conditions). ORB-SLAM2's RGB-D value is 0.75, its monocular one 0.9: 0.85
  // keeps consecutive keyframes sharing most of their points, so local BA ties each new pose to several
  // well-constrained ones; on the 20 s synthetic room laps (static_loop seeds 1-10, --deterministic) the lap closes
  // at 5.4-8.4 mm instead of 6.6-11.6 mm, with 57-121 keyframes instead of 22-32; 0.9 gives 4.4-6.1 mm but 119-192
  // keyframes and a fifth of the speed of --deterministic runs. The synthetic walking presets' static twins gain
  // 0-8 %, the Bonn crowd slice is unchanged; the cost: TUM fr2 desk's first 50 frames, 5.4 mm (mean over 8 start
  // offsets) instead of 4.9 (0.8: 4.9, but normal-run laps then close under 1 cm on 17 of 20 runs, not 19).
  double keyframe_ref_ratio = 0.85;
  // Tracking.keyFrameMinRotation (degrees) / keyFrameMinBaseline (share of the frame's median keypoint depth) /
  // keyFrameMoverShare: a camera that stays within the first two of its reference keyframe while movers cover at
  // least keyFrameMoverShare of the image (its dynamic mask) sees the scene that keyframe already holds; the
  // points it stops tracking are hidden by the movers, not out of view. A keyframe there adds no view and no
  // parallax, only a copy of the scene anchored at a pose no better known than the reference's, and points on the
  // movers' edges; so none is made while tracking is sound (at least a quarter of the reference's points, and as
  // many map points as closeTrackedMax, ORB-SLAM2's own bar for a well-tracked RGB-D frame). With twice
  // localMinInliers (60) as the bar, Bonn crowd frame 71 went from 69 tracked points to 20 (people stepped in front
  // of what was left) and was lost for 13 frames in 1 of ~10 normal runs: a frame tracking under 100 points is
  // one crowded frame away from a loss and should give the map its view. ORB-SLAM2 has no such rule: with a still
  // camera and people walking past it makes a keyframe each time they cover a quarter of the points (15-19 in
  // 10 s of the synthetic walking_static against 1 without the people, 69 in the 9 s of Bonn crowd, 38 with the
  // rule). 1.5 deg and 1.5 %: the view then
  // overlaps the reference's by ~97 % (60 deg field of view) and the parallax at the median depth stays under
  // ~1 deg; 3 deg and 3 % (Bonn: 25 keyframes) cost the synthetic walking_halfsphere, whose camera orbits slowly,
  // accuracy on 2 of 5 seeds (1.60-1.63x its static twin instead of 1.15-1.49x). 0.1: movers must hide at
  // least a tenth of the view to explain a loss of the quarter of the points that triggers a keyframe; without
  // them (a static scene) ORB-SLAM2's rule stands, whose frequent keyframes refine a slowly explored map (TUM fr2
  // desk, 50 frames: 4.45 mm ATE, 5.0 mm with the rule applied everywhere). Any of the three 0 = off.
  double keyframe_min_rotation_deg = 1.5;
  double keyframe_min_baseline = 0.015;
  double keyframe_mover_share = 0.1;
  // Tracking.keyFrameViewRotation (degrees) / keyFrameViewBaseline (share of the median keypoint depth): a camera
  // that has turned or moved this far from its reference keyframe may make a keyframe even while local mapping
  // is busy (beside ORB-SLAM2's "mapping idle" and "maxFrames passed", under the same tracked-points test). ORB-SLAM2's
  // rule ties the keyframe density to the feed: a folder read faster than the sensor keeps mapping busy, and a 20 s
  // room lap (static_loop) got 20-34 keyframes against 57-121 when mapping keeps up (--deterministic); the lap's
  // drift, which the loop closure has to absorb, grows with that spacing: seeds 1-10 in normal runs closed at
  // 5.9-10.4 mm with keyFrameRefRatio 0.85 alone, 4.9-9.0 and 5.8-10.5 mm (two runs, 40-64 keyframes) with this.
  // 5 deg: the view shifts by ~8 % of a 60 deg field of view, about the share of points whose loss triggers a
  // keyframe (keyFrameRefRatio); 5 % of the median depth gives a point there ~3 deg of parallax. 0 = off.
  double keyframe_view_rotation_deg = 5.0;
  double keyframe_view_baseline = 0.05;
  // Tracking.closeTrackedMax: fewer tracked close points ... / closeUntrackedMin: ... and this many untracked ones
  // -> new keyframe. Defaults scale with ORBextractor.nFeatures (closeTrackedMaxFor / closeUntrackedMinFor).
  int close_tracked_max = 100;
  int close_untracked_min = 70;
  int new_points_min = 100;          // Tracking.newPointsMin: depth points created per keyframe (at least, closest first)
  int vo_points_min = 100;           // Tracking.voPointsMin: temporary points from the last frame's depth
  // Tracking.recoveryFrames: for this many frames after tracking was lost, the local map around the last tracked
  // pose is searched first (wide window, relocMinInliers needed), before the global relocaliser. Losses in
  // dynamic scenes are mostly people covering the view for a moment while the camera stays near where it was
  // (ORB-SLAM3's "recently lost" state); the relocaliser needs a keyframe that looks like the frame, this only
  // needs enough of the nearby map. 30 = one second at 30 Hz; 0 = off.
  int recovery_frames = 30;
  // Tracking.recoverySearchRadius: its window (ORB-SLAM2 radius units: x 2.5-4 px x level scale). 15 covers the
  // image motion of ~0.5 s of hand-held rotation at 30 deg/s (~8 deg, ~75 px at f = 540) at the middle levels.
  double recovery_search_radius = 15;
  ExternalPosePolicy external_pose = ExternalPosePolicy::kCompete;  // Tracking.externalPose
  // Localization mode (`run --load-map FILE --localize`, not a settings key): track against the map without
  // adding keyframes or points (ORB-SLAM2's localization mode). The map must have been loaded; the first frame
  // is localised by the relocaliser (cold start), as is every frame after a loss.
  bool localization_only = false;
  geometry::PoseOptimizerOptions pose;  // Tracking.chi2Mono / chi2Stereo / poseRounds / poseIterations
  // Tracking.photometric: refine each tracked frame's pose against its reference keyframe's pixels jointly with
  // its feature inliers (photometric_refiner.h). The one-frame pose error falls 2-5x on synthetic sequences and
  // by a quarter on the Bonn crowd slice (docs/experiments/photometric-refinement.md); off saves its ~2 ms.
  bool photometric = true;
  geometry::PhotometricOptions photometric_options;
  match::MatchingOptions matching;      // Matching.*
  RelocalizerOptions relocalization;    // Relocalization.*
  void check() const;
};

}  // namespace amos::tracking
