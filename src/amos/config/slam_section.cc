#include "amos/config/slam_section.h"

#include <algorithm>
#include <cmath>

namespace amos::config {

KeySection trackingKeys(tracking::TrackerOptions& o, const double& fps, const int& num_features) {
  KeySection s{"Tracking"};
  s.prepare = [&o, &fps, &num_features] {
    if (fps > 0) o.max_frames_between_keyframes = std::max(1, static_cast<int>(std::lround(fps)));
    if (num_features > 0) {
      o.close_tracked_max = tracking::closeTrackedMaxFor(num_features);
      o.close_untracked_min = tracking::closeUntrackedMinFor(num_features);
    }
  };
  s.add("Tracking.initMinDepthPoints", &o.init_min_depth_points, "keypoints with depth needed to start the map");
  s.add("Tracking.motionSearchRadius", &o.motion_search_radius, "window of the motion-model search (px at level 0)");
  s.add("Tracking.motionMinMatches", &o.motion_min_matches,
        "motion-model matches below which the window is doubled, then the model fails");
  s.add("Tracking.minMapMatches", &o.min_map_matches, "inliers with map points to accept a frame-to-frame step");
  s.add("Tracking.referenceMinMatches", &o.reference_min_matches,
        "brute-force matches needed to try the reference keyframe");
  s.add("Tracking.localSearchRadius", &o.local_search_radius, "window of the local-map search (px at level 0)");
  s.add("Tracking.relocSearchRadius", &o.reloc_search_radius,
        "window of the local-map search in the frames right after a relocalisation");
  s.add("Tracking.localMinInliers", &o.local_min_inliers, "inliers for a tracked frame");
  s.add("Tracking.relocMinInliers", &o.reloc_min_inliers,
        "inliers for a tracked frame right after a relocalisation (at least `localMinInliers`)");
  s.add("Tracking.maxLocalKeyFrames", &o.max_local_keyframes, "keyframes in the local map at most");
  s.add("Tracking.maxFrames", &o.max_frames_between_keyframes, "a keyframe at least this often when tracking is weak")
      .defaultIs("Camera.fps");
  s.add("Tracking.minFrames", &o.min_frames_between_keyframes, "frames between keyframes at least");
  s.add("Tracking.keyFrameRefRatio", &o.keyframe_ref_ratio,
        "new keyframe when the frame tracks fewer points than this share of the reference keyframe's");
  s.add("Tracking.keyFrameMinRotation", &o.keyframe_min_rotation_deg,
        "no keyframe while tracking is sound and the camera has turned less than this from its reference keyframe "
        "(degrees) ...");
  s.add("Tracking.keyFrameMinBaseline", &o.keyframe_min_baseline,
        "... and moved less than this share of the median keypoint depth ...");
  s.add("Tracking.keyFrameMoverShare", &o.keyframe_mover_share,
        "... while movers (the dynamic mask) cover at least this share of the image (any of the three 0 = off, "
        "ORB-SLAM2's rule)");
  s.add("Tracking.keyFrameViewRotation", &o.keyframe_view_rotation_deg,
        "a keyframe may be made while local mapping is busy once the camera has turned this far (degrees) from its "
        "reference keyframe ...; 0 = off");
  s.add("Tracking.keyFrameViewBaseline", &o.keyframe_view_baseline,
        "... or moved this share of the median keypoint depth; 0 = off");
  s.add("Tracking.closeTrackedMax", &o.close_tracked_max, "... or when fewer close points than this are tracked")
      .defaultIs("ORBextractor.nFeatures / 10");
  s.add("Tracking.closeUntrackedMin", &o.close_untracked_min, "... and at least this many close points are not")
      .defaultIs("ORBextractor.nFeatures * 7 / 100");
  s.add("Tracking.newPointsMin", &o.new_points_min, "depth points a new keyframe creates at least, closest first");
  s.add("Tracking.voPointsMin", &o.vo_points_min, "temporary points made from the last frame's depth");
  s.add("Tracking.recoveryFrames", &o.recovery_frames,
        "for this many frames after a loss, first search the last local map around the last tracked pose (wide "
        "window, PnP RANSAC, `relocMinInliers`), then the global relocaliser; 0 = off");
  s.add("Tracking.recoverySearchRadius", &o.recovery_search_radius, "window of that search (ORB-SLAM2 radius units)");
  s.add("Tracking.externalPose", &o.external_pose,
        {{"replace", tracking::ExternalPosePolicy::kReplace}, {"compete", tracking::ExternalPosePolicy::kCompete}},
        "the front end's initial pose competes with the motion model or replaces it");
  s.add("Tracking.chi2Mono", &o.pose.chi2_mono,
        "outlier threshold of pose optimisation without depth (chi-square 95 %)");
  s.add("Tracking.chi2Stereo", &o.pose.chi2_stereo, "... with depth (chi-square 95 %, 3 dof)");
  s.add("Tracking.poseRounds", &o.pose.rounds, "outlier classification rounds of pose optimisation");
  s.add("Tracking.poseIterations", &o.pose.iterations_per_round, "iterations per round");
  s.add("Tracking.poseRobustRounds", &o.pose.robust_rounds, "first rounds with the Huber kernel");
  s.add("Tracking.photometric", &o.photometric,
        "refine each frame's pose against its reference keyframe's pixels jointly with its feature inliers");

  s.add("Matching.thHigh", &o.matching.th_high, "Hamming distance limit of projection matches");
  s.add("Matching.thLow", &o.matching.th_low, "Hamming distance limit of brute-force matches (at most `thHigh`)");
  s.add("Matching.localRatio", &o.matching.local_ratio, "best / second best on the same level in the local-map search");
  s.add("Matching.bruteForceRatio", &o.matching.brute_force_ratio, "Lowe ratio of brute-force matches to a keyframe");
  s.add("Matching.checkOrientation", &o.matching.check_orientation, "keep matches in the three dominant rotation bins");

  s.add("Relocalization.candidates", &o.relocalization.num_candidates, "keyframes tried, best thumbnails first");
  s.add("Relocalization.minMatches", &o.relocalization.min_matches, "brute-force matches to try PnP on a keyframe");
  s.add("Relocalization.matchRatio", &o.relocalization.match_ratio, "Lowe ratio of those matches");
  s.add("Relocalization.minInliers", &o.relocalization.min_inliers, "inliers needed to accept a pose");
  s.add("Relocalization.reprojectionThreshold", &o.relocalization.pnp.reprojection_threshold_px,
        "PnP RANSAC inlier threshold (undistorted px)");
  s.add("Relocalization.ransacIterations", &o.relocalization.pnp.max_iterations, "PnP RANSAC iterations at most");
  s.add("Relocalization.seed", &o.relocalization.pnp.seed, "PnP RANSAC seed");
  return s;
}

KeySection mappingKeys(mapping::LocalMappingOptions& o, map::CovisibilityOptions& covisibility) {
  KeySection s{"Local mapping"};
  s.add("Mapping.covisibilityMinWeight", &covisibility.min_weight, "shared points for a covisibility link");
  s.add("Mapping.recentFoundRatio", &o.recent_found_ratio,
        "a new point found in fewer than this share of the frames that should see it is culled");
  s.add("Mapping.recentMinObservations", &o.recent_min_observations,
        "... and one with fewer observations two keyframes later");
  s.add("Mapping.redundantRatio", &o.redundant_ratio, "a keyframe whose close points are this often seen ...");
  s.add("Mapping.redundantObservers", &o.redundant_observers, "... by this many other keyframes is culled");
  s.add("Mapping.cullKeyFrames", &o.cull_keyframes, "cull redundant keyframes");
  s.add("Mapping.triangulationNeighbors", &o.new_points.neighbors,
        "covisible keyframes new points are triangulated with");
  s.add("Mapping.triangulationMaxDistance", &o.new_points.max_distance, "Hamming distance limit of those matches");
  s.add("Mapping.triangulationRatio", &o.new_points.ratio, "best / second best along the epipolar line");
  s.add("Mapping.maxCosParallax", &o.new_points.max_cos_parallax, "cosine of the smallest parallax of a new point");
  s.add("Mapping.fuseNeighbors", &o.fusion.neighbors, "covisible keyframes whose points are fused with the new one's");
  s.add("Mapping.fuseSecondNeighbors", &o.fusion.second_neighbors, "neighbours of each of those also fused");
  s.add("Mapping.fuseRadius", &o.fusion.radius, "fusion window (px x scale)");
  s.add("Mapping.fuseMaxDistance", &o.fusion.max_distance, "Hamming distance limit of fusion");
  s.add("Mapping.dynamicCullMinHits", &o.dynamic_culling.min_hits,
        "a point seen visible inside dynamic regions in at least this many frames ...");
  s.add("Mapping.dynamicCullRatio", &o.dynamic_culling.min_ratio, "... and this share of its masked views is removed");

  s.add("LocalBA.enabled", &o.local_ba, "local bundle adjustment in the mapping thread");
  s.add("LocalBA.iterationsRobust", &o.ba.iterations_robust, "iterations with the Huber loss");
  s.add("LocalBA.iterationsRefine", &o.ba.iterations_refine, "then iterations without the outliers and robust loss");
  s.add("LocalBA.maxKeyFrames", &o.ba.max_keyframes,
        "the new keyframe and at most this many of its most covisible neighbours are adjusted; other observers stay "
        "fixed (0 = every covisible keyframe, ORB-SLAM2's window)");
  s.add("LocalBA.chi2Mono", &o.ba.chi2_mono, "outlier threshold without depth (chi-square 95 %)");
  s.add("LocalBA.chi2Stereo", &o.ba.chi2_stereo, "outlier threshold with depth (chi-square 95 %, 3 dof)");
  s.add("LocalBA.threads", &o.ba.num_threads, "Ceres threads (1 keeps `--deterministic` runs bit-identical)");
  return s;
}

KeySection loopKeys(loop::LoopClosingOptions& o, const mapping::LocalMappingOptions& mapping) {
  KeySection s{"Loop closing"};
  s.prepare = [&o, &mapping] { o.fusion = mapping.fusion; };
  s.add("Loop.enabled", &o.enabled, "look for loops after every keyframe (in the mapping thread)");
  s.add("Loop.essentialMinWeight", &o.essential_min_weight,
        "covisibility links kept in the pose graph (with the spanning tree and the loop links)");
  s.add("Loop.poseGraphIterations", &o.pose_graph.max_iterations, "Levenberg-Marquardt iterations of the pose graph");
  s.add("Loop.bagOfWords", &o.bag_of_words,
        "loop candidates from the bag of words (Place.vocabulary) instead of the thumbnails");
  s.add("Loop.globalBundleAdjustment", &o.global_bundle_adjustment,
        "after a loop closure, bundle-adjust the whole map (every keyframe and point)");
  s.add("Loop.minKeyFrames", &o.detector.min_keyframes, "map size before the first search");
  s.add("Loop.minKeyFrameGap", &o.detector.min_keyframe_gap, "keyframes between two closures");
  s.add("Loop.candidates", &o.detector.candidates,
        "keyframes verified per search (best thumbnails among those not covisible)");
  s.add("Loop.minMatches", &o.detector.min_matches, "descriptor matches needed to try PnP on a candidate");
  s.add("Loop.matchRatio", &o.detector.match_ratio, "Lowe ratio of those matches");
  s.add("Loop.minInliers", &o.detector.min_inliers,
        "inliers after projecting the loop neighbourhood (at least `minMatches`): stricter than relocalisation, "
        "since a false loop bends the whole map");
  s.add("Loop.consistency", &o.detector.consistency,
        "consecutive keyframes whose loop candidates must point at the same place before one is verified; 0 = off");
  s.add("Loop.singleKeyFrameInliers", &o.detector.single_keyframe_inliers,
        "a candidate not yet consistent is verified too and accepted on one keyframe with this many inliers "
        "(0 = only consistent candidates, ORB-SLAM2's rule; else at least `minInliers`)");
  s.add("Loop.reprojectionThreshold", &o.detector.pnp.reprojection_threshold_px,
        "PnP RANSAC inlier threshold (undistorted px)");
  return s;
}

}  // namespace amos::config
