#include "amos/config/slam_section.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "amos/core/error.h"

namespace amos::config {

namespace {

tracking::ExternalPosePolicy parseExternalPose(const YamlReader& in, const std::string& text) {
  if (text == "replace") return tracking::ExternalPosePolicy::kReplace;
  if (text == "compete") return tracking::ExternalPosePolicy::kCompete;
  throw core::Error(fmt::format("{}: Tracking.externalPose must be 'replace' or 'compete', got '{}'",
                                in.where("Tracking.externalPose"), text));
}

}  // namespace

void readTrackingSection(YamlReader& in, double fps, tracking::TrackerOptions& o) {
  if (fps > 0) o.max_frames_between_keyframes = std::max(1, static_cast<int>(std::lround(fps)));
  in.read("Tracking.initMinDepthPoints", o.init_min_depth_points);
  in.read("Tracking.motionSearchRadius", o.motion_search_radius);
  in.read("Tracking.motionMinMatches", o.motion_min_matches);
  in.read("Tracking.minMapMatches", o.min_map_matches);
  in.read("Tracking.referenceMinMatches", o.reference_min_matches);
  in.read("Tracking.localSearchRadius", o.local_search_radius);
  in.read("Tracking.relocSearchRadius", o.reloc_search_radius);
  in.read("Tracking.localMinInliers", o.local_min_inliers);
  in.read("Tracking.relocMinInliers", o.reloc_min_inliers);
  in.read("Tracking.maxLocalKeyFrames", o.max_local_keyframes);
  in.read("Tracking.maxFrames", o.max_frames_between_keyframes);
  in.read("Tracking.minFrames", o.min_frames_between_keyframes);
  in.read("Tracking.keyFrameRefRatio", o.keyframe_ref_ratio);
  in.read("Tracking.closeTrackedMax", o.close_tracked_max);
  in.read("Tracking.closeUntrackedMin", o.close_untracked_min);
  in.read("Tracking.newPointsMin", o.new_points_min);
  in.read("Tracking.voPointsMin", o.vo_points_min);
  in.read("Tracking.recoveryFrames", o.recovery_frames);
  in.read("Tracking.recoverySearchRadius", o.recovery_search_radius);
  std::string external = o.external_pose == tracking::ExternalPosePolicy::kReplace ? "replace" : "compete";
  in.read("Tracking.externalPose", external);
  o.external_pose = parseExternalPose(in, external);
  in.read("Tracking.chi2Mono", o.pose.chi2_mono);
  in.read("Tracking.chi2Stereo", o.pose.chi2_stereo);
  in.read("Tracking.poseRounds", o.pose.rounds);
  in.read("Tracking.poseIterations", o.pose.iterations_per_round);
  in.read("Tracking.poseRobustRounds", o.pose.robust_rounds);

  in.read("Matching.thHigh", o.matching.th_high);
  in.read("Matching.thLow", o.matching.th_low);
  in.read("Matching.localRatio", o.matching.local_ratio);
  in.read("Matching.bruteForceRatio", o.matching.brute_force_ratio);
  in.read("Matching.checkOrientation", o.matching.check_orientation);

  in.read("Relocalization.candidates", o.relocalization.num_candidates);
  in.read("Relocalization.minMatches", o.relocalization.min_matches);
  in.read("Relocalization.matchRatio", o.relocalization.match_ratio);
  in.read("Relocalization.minInliers", o.relocalization.min_inliers);
  in.read("Relocalization.reprojectionThreshold", o.relocalization.pnp.reprojection_threshold_px);
  in.read("Relocalization.ransacIterations", o.relocalization.pnp.max_iterations);
  int seed = static_cast<int>(o.relocalization.pnp.seed);
  in.read("Relocalization.seed", seed);
  o.relocalization.pnp.seed = static_cast<unsigned>(seed);
}

void readMappingSection(YamlReader& in, mapping::LocalMappingOptions& o, map::CovisibilityOptions& covisibility) {
  in.read("Mapping.covisibilityMinWeight", covisibility.min_weight);
  in.read("Mapping.recentFoundRatio", o.recent_found_ratio);
  in.read("Mapping.recentMinObservations", o.recent_min_observations);
  in.read("Mapping.redundantRatio", o.redundant_ratio);
  in.read("Mapping.redundantObservers", o.redundant_observers);
  in.read("Mapping.cullKeyFrames", o.cull_keyframes);
  in.read("Mapping.triangulationNeighbors", o.new_points.neighbors);
  in.read("Mapping.triangulationMaxDistance", o.new_points.max_distance);
  in.read("Mapping.triangulationRatio", o.new_points.ratio);
  in.read("Mapping.maxCosParallax", o.new_points.max_cos_parallax);
  in.read("Mapping.fuseNeighbors", o.fusion.neighbors);
  in.read("Mapping.fuseSecondNeighbors", o.fusion.second_neighbors);
  in.read("Mapping.fuseRadius", o.fusion.radius);
  in.read("Mapping.fuseMaxDistance", o.fusion.max_distance);
  in.read("Mapping.dynamicCullMinHits", o.dynamic_culling.min_hits);
  in.read("Mapping.dynamicCullRatio", o.dynamic_culling.min_ratio);

  in.read("LocalBA.enabled", o.local_ba);
  in.read("LocalBA.iterationsRobust", o.ba.iterations_robust);
  in.read("LocalBA.iterationsRefine", o.ba.iterations_refine);
  in.read("LocalBA.maxKeyFrames", o.ba.max_keyframes);
  in.read("LocalBA.chi2Mono", o.ba.chi2_mono);
  in.read("LocalBA.chi2Stereo", o.ba.chi2_stereo);
  in.read("LocalBA.threads", o.ba.num_threads);
}

void readLoopSection(YamlReader& in, const mapping::LocalMappingOptions& mapping, loop::LoopClosingOptions& o) {
  o.fusion = mapping.fusion;
  in.read("Loop.enabled", o.enabled);
  in.read("Loop.essentialMinWeight", o.essential_min_weight);
  in.read("Loop.poseGraphIterations", o.pose_graph.max_iterations);
  in.read("Loop.minKeyFrames", o.detector.min_keyframes);
  in.read("Loop.minKeyFrameGap", o.detector.min_keyframe_gap);
  in.read("Loop.candidates", o.detector.candidates);
  in.read("Loop.minMatches", o.detector.min_matches);
  in.read("Loop.matchRatio", o.detector.match_ratio);
  in.read("Loop.minInliers", o.detector.min_inliers);
  in.read("Loop.consistency", o.detector.consistency);
  in.read("Loop.reprojectionThreshold", o.detector.pnp.reprojection_threshold_px);
}

}  // namespace amos::config
