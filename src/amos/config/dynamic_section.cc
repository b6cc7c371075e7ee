#include "amos/config/dynamic_section.h"

namespace amos::config {

namespace {

std::vector<std::pair<std::string, dynamic::DynamicMode>> dynamicModes() {
  std::vector<std::pair<std::string, dynamic::DynamicMode>> out;
  for (auto mode : {dynamic::DynamicMode::kNone, dynamic::DynamicMode::kPrior, dynamic::DynamicMode::kGeometry,
                    dynamic::DynamicMode::kFull}) {
    out.emplace_back(dynamic::toString(mode), mode);
  }
  return out;
}

}  // namespace

KeySection dynamicKeys(dynamic::DynamicOptions& o) {
  KeySection s{"Front end"};
  s.add("Dynamic.mode", &o.mode, dynamicModes(),
        "which stages make the dynamic mask: none (plain SLAM), prior (person segmentation), geometry (superpixel "
        "clusters judged by reprojection and epipolar tests), full (both, the paper's system)");
  s.add("Dynamic.priorMaskedExtraction", &o.prior_masked_extraction,
        "ORB features are detected outside the (previous frame's) person masks in the first place");
  s.add("Dynamic.priorMaskedExtractionCoverage", &o.prior_masked_extraction_coverage,
        "... once the mask covers at least this share of the image (at any coverage before the map exists)");
  s.add("Dynamic.Prior.interval", &o.prior.interval,
        "the network segments every interval-th frame (1 = every frame, the paper)");
  s.add("Dynamic.Prior.lag", &o.prior.lag,
        "a segmentation is used this many frames later, carried there by the tracks (0 = wait for it)");
  s.add("Dynamic.Prior.detectEvery", &o.prior.detect_every,
        "the person detector runs on every detectEvery-th segmentation, the others mask the last one's people "
        "again (1 = every segmentation detects)");
  s.add("Dynamic.Prior.minTracks", &o.prior.min_tracks, "tracks inside a person needed to measure its motion");
  s.add("Dynamic.Prior.holdMissed", &o.prior.hold_missed,
        "segmentations a person is carried on for after the network no longer finds it");
  s.add("Dynamic.Prior.liveWait", &o.prior.live_wait,
        "1 = with a paced or live source stage B waits for a late segmentation as a folder run does; 0 = the "
        "masks are carried on meanwhile (at most one interval longer)");
  s.add("Dynamic.Prior.auditPredictions", &o.prior.audit_predictions,
        "also segment every frame and score the carried masks against it (for measurement only)");

  s.add("Dynamic.Superpixel.count", &o.superpixel.num_superpixels, "superpixels over the image");
  s.add("Dynamic.Superpixel.scale", &o.superpixel.scale,
        "working resolution of the superpixels, relative to the image");
  s.add("Dynamic.Superpixel.colourScale", &o.superpixel.colour_scale, "Lab distance weighing as much as one grid step");
  s.add("Dynamic.Superpixel.depthScale", &o.superpixel.depth_scale_m,
        "depth difference (m) weighing as much as one grid step");
  s.add("Dynamic.Superpixel.iterations", &o.superpixel.iterations, "SLIC rounds");

  s.add("Dynamic.Cluster.count", &o.cluster.num_clusters, "k-means clusters of the superpixels");
  s.add("Dynamic.Cluster.depthScale", &o.cluster.depth_scale_m,
        "depth difference (m) weighing as much as one cluster cell of image distance");
  s.add("Dynamic.Cluster.maxIterations", &o.cluster.max_iterations, "Lloyd rounds at most");
  s.add("Dynamic.Cluster.seed", &o.cluster.seed, "k-means++ seed");

  s.add("Dynamic.Corners.maxCorners", &o.tracking.max_corners, "Shi-Tomasi corners tracked per frame at most");
  s.add("Dynamic.Corners.qualityLevel", &o.tracking.quality_level, "corner response relative to the best corner's");
  s.add("Dynamic.Corners.minDistance", &o.tracking.min_distance_px, "distance between corners at least (px)");
  s.add("Dynamic.Corners.detectionScale", &o.tracking.detection_scale,
        "corners are detected on the image scaled by this, and tracked at full resolution");
  s.add("Dynamic.LK.window", &o.tracking.lk_window, "side of the LK window (px, odd)");
  s.add("Dynamic.LK.pyramidLevels", &o.tracking.lk_levels, "LK pyramid levels above the image");
  s.add("Dynamic.LK.maxIterations", &o.tracking.lk_max_iterations, "LK iterations per level at most");
  s.add("Dynamic.LK.epsilon", &o.tracking.lk_epsilon, "LK stops on a level when its step is below this (px)");
  s.add("Dynamic.LK.forwardBackwardThreshold", &o.tracking.forward_backward_px,
        "a track must come back this close to where it started (px)");
  s.add("Dynamic.LK.forwardBackward", &o.tracking.forward_backward_check,
        "1 = the corner tracks are checked by tracking them back (twice the LK cost), 0 = forward only");

  s.add("Dynamic.Reprojection.cauchyScale", &o.reprojection.cauchy_scale_px,
        "scale of the Cauchy loss on the reprojection errors (px)");
  s.add("Dynamic.Reprojection.threshold", &o.reprojection.candidate_threshold_px,
        "a cluster whose equivalent error exceeds this is a candidate (px)");
  s.add("Dynamic.Reprojection.minPoints", &o.reprojection.min_points_per_cluster,
        "errors a cluster needs to be scored");
  s.add("Dynamic.Reprojection.maxDepth", &o.reprojection.max_depth_m, "depths beyond this are not used (m)");
  s.add("Dynamic.Reprojection.depthEdgeRatio", &o.reprojection.depth_edge_ratio,
        "depth spread around a point, as a share of its depth, that puts it on a depth edge");
  s.add("Dynamic.Reprojection.refitPose", &o.reprojection.refit_pose,
        "refit the pose on the tracks outside the candidate and prior regions and judge every cluster under it");
  s.add("Dynamic.Reprojection.refitMinPoints", &o.reprojection.refit_min_points, "inliers the refit needs");
  s.add("Dynamic.Reprojection.confirmSigmas", &o.reprojection.confirm_sigmas,
        "under the refitted pose a cluster is dynamic above this many times the static tracks' noise ...");
  s.add("Dynamic.Reprojection.confirmThreshold", &o.reprojection.confirm_threshold_px, "... and above this (px)");
  s.add("Dynamic.Reprojection.intervalErrors", &o.reprojection.interval_errors,
        "tracks without a trusted depth score the smallest error their window's depths allow (0 = left out)");

  s.add("Dynamic.Epipolar.ransacThreshold", &o.epipolar.ransac_threshold_px,
        "inlier distance of the fundamental-matrix fit (px)");
  s.add("Dynamic.Epipolar.threshold", &o.epipolar.dynamic_threshold_px,
        "a track is dynamic beyond this distance from its epipolar line (px, at least `ransacThreshold`)");
  s.add("Dynamic.Epipolar.confidence", &o.epipolar.confidence, "RANSAC confidence");
  s.add("Dynamic.Epipolar.maxIterations", &o.epipolar.max_iterations, "RANSAC iterations at most");
  s.add("Dynamic.Epipolar.minDynamicPoints", &o.epipolar.min_dynamic_points,
        "epipolar violators that make a region dynamic");
  s.add("Dynamic.Epipolar.minFitPoints", &o.epipolar.min_fit_points,
        "tracks outside the potential motion regions needed to fit F on them alone");
  s.add("Dynamic.Epipolar.seed", &o.epipolar.seed, "RANSAC seed");

  s.add("Dynamic.Boundary.radius", &o.boundary.search_radius_px,
        "search radius for the cluster on the other side of a border (px)");
  s.add("Dynamic.Boundary.borderMargin", &o.boundary.border_margin_px,
        "a superpixel this close to the image edge is a border block (px)");
  s.add("Dynamic.Boundary.borderBlocks", &o.boundary.border_blocks,
        "1 = superpixels at the image edge take no part in the decisions (paper), 0 = only tracks within half an LK "
        "window of the edge");
  s.add("Dynamic.Boundary.superpixelMask", &o.boundary.superpixel_mask,
        "1 = the mask is decided per superpixel, 0 = it is the union of the dynamic clusters");
  s.add("Dynamic.Boundary.seedOutsideClusters", &o.boundary.seed_outside_clusters,
        "superpixels outside the dynamic clusters whose own tracks move under the refitted pose are seeds too");
  s.add("Dynamic.Temporal.excludeFromFits", &o.temporal.exclude_last_mask_from_fits,
        "tracks starting in the last frame's mask take no part in the last-frame initial-pose model, the pose refit "
        "and the F fit");
  s.add("Dynamic.Depth.enabled", &o.depth.enabled,
        "superpixels whose depth moved against the last frame's (under the judged pose) are dynamic evidence too")
      .experimental();
  s.add("Dynamic.Depth.sampleStep", &o.depth.sample_step_px, "every step-th pixel in x and y is a depth sample");
  s.add("Dynamic.Depth.noiseBase", &o.depth.noise_base_m, "axial depth noise sigma(z) = base + quadratic (z - offset)^2 (m)");
  s.add("Dynamic.Depth.noiseQuadratic", &o.depth.noise_quadratic, "... its quadratic term (1/m)");
  s.add("Dynamic.Depth.noiseOffset", &o.depth.noise_offset_m, "... its offset (m)");
  s.add("Dynamic.Depth.maxDepth", &o.depth.max_depth_m, "depth samples farther than this (m) in either frame do not count");
  s.add("Dynamic.Depth.sigmas", &o.depth.sigmas,
        "a superpixel moves when its median depth residual is this many standard errors from zero");
  s.add("Dynamic.Depth.minResidual", &o.depth.min_residual_m, "... and at least this far (m)");
  s.add("Dynamic.Depth.minRelativeResidual", &o.depth.min_relative_residual,
        "... and at least this share of the depth (a real sensor's depth bias varies over the image)");
  s.add("Dynamic.Depth.minSamples", &o.depth.min_samples, "valid depth samples a superpixel needs to be judged");
  s.add("Dynamic.Depth.violationSigmas", &o.depth.violation_sigmas,
        "a sample violates free space when the last frame saw a surface this many sigma behind its point");
  s.add("Dynamic.Depth.violationShare", &o.depth.violation_share,
        "a superpixel moves when this share of its samples violate free space ...");
  s.add("Dynamic.Depth.minViolations", &o.depth.min_violations, "... and at least this many");
  s.add("Dynamic.Depth.unscoredClusterSuperpixels", &o.depth.unscored_cluster_superpixels,
        "a cluster too poor in tracks to be scored is dynamic with this many moving superpixels");
  s.add("Dynamic.Depth.baselineFrames", &o.depth.baseline_frames,
        "the depth is also compared with that of the frame this many frames back, for slow movers (0 = off)");
  s.add("Dynamic.Depth.baselineRelativeResidual", &o.depth.baseline_relative_residual,
        "minRelativeResidual of that comparison");
  s.add("Dynamic.Depth.clusterShare", &o.depth.cluster_share,
        "a cluster is dynamic when this share of its depth samples lies in moving superpixels");
  s.add("Dynamic.BaselineTracks.enabled", &o.baseline_tracks.enabled,
        "the current frame's points are also tracked into the frame Dynamic.Depth.baselineFrames back and judged "
        "by their reprojection error there, for movers too slow for one frame")
      .experimental();
  s.add("Dynamic.BaselineTracks.sigmas", &o.baseline_tracks.sigmas,
        "a point moves when its error (less the median error of all points) exceeds this many noise scales ...");
  s.add("Dynamic.BaselineTracks.minMotion", &o.baseline_tracks.min_motion_px, "... and this many pixels");
  s.add("Dynamic.BaselineTracks.minVotes", &o.baseline_tracks.min_votes,
        "moving points a superpixel or a cluster needs to move");
  s.add("Dynamic.BaselineTracks.clusterShare", &o.baseline_tracks.cluster_share,
        "a cluster is dynamic when this share of its points moves");
  s.add("Dynamic.BaselineTracks.growDissimilarity", &o.baseline_tracks.grow_dissimilarity,
        "largest Eq. 1 dissimilarity (no position term) of one step of the surface growth from the rigid movers' "
        "superpixels (`Dynamic.RigidMovers.growOverSurface`)");

  s.add("Dynamic.RigidMovers.enabled", &o.rigid_movers.enabled,
        "the rigid motions of the moving long-baseline points are fitted and every textured sample of the frame is "
        "judged by which motion, the static world's or a mover's, explains it over the baseline (acts only with "
        "Dynamic.BaselineTracks.enabled)")
      .experimental();
  s.add("Dynamic.RigidMovers.minInliers", &o.rigid_movers.min_inliers, "moving points one rigid motion must explain");
  s.add("Dynamic.RigidMovers.inlierPx", &o.rigid_movers.inlier_px,
        "reprojection error of such a point over the baseline [px]");
  s.add("Dynamic.RigidMovers.maxMovers", &o.rigid_movers.max_movers, "rigid motions fitted at most");
  s.add("Dynamic.RigidMovers.sampleStep", &o.rigid_movers.sample_step_px, "grid step of the samples [px]");
  s.add("Dynamic.RigidMovers.minSeparation", &o.rigid_movers.min_separation_px,
        "a sample decides only where the hypotheses put it this far apart [px]");
  s.add("Dynamic.RigidMovers.intensityMargin", &o.rigid_movers.intensity_margin,
        "a hypothesis wins a sample when its 3x3 patch differs from the baseline image by this many grey levels less");
  s.add("Dynamic.RigidMovers.minSamples", &o.rigid_movers.min_samples,
        "samples a superpixel needs for a mover (and twice those for the static world) to move");
  s.add("Dynamic.RigidMovers.regionReach", &o.rigid_movers.region_reach_px,
        "a mover speaks for the samples within this many pixels of the box around its points");
  s.add("Dynamic.RigidMovers.minGradient", &o.rigid_movers.min_gradient,
        "RMS intensity gradient a sample needs along the direction separating the hypotheses [grey levels per px]");
  s.add("Dynamic.RigidMovers.growOverSurface", &o.rigid_movers.grow_over_surface,
        "the mask may grow from the superpixels that follow a rigid mover over unmeasured superpixels of the same "
        "surface (steps of at most Dynamic.BaselineTracks.growDissimilarity), outside the dynamic clusters too, within "
        "Dynamic.RigidMovers.regionReach of the movers' points")
      .experimental();

  s.add("Dynamic.InitialPose.selectByCoverage", &o.initial_pose.select_by_coverage,
        "1 = of the initial-pose hypotheses and models with at least half the most inliers, the one whose inliers "
        "cover the most image cells wins; 0 = the most inliers");
  s.add("Dynamic.InitialPose.inlierThreshold", &o.initial_pose.inlier_threshold_px,
        "reprojection error of an inlier of the initial-pose models (px)");
  s.add("Dynamic.InitialPose.keyframeMaxPoints", &o.initial_pose.keyframe_max_points,
        "reference-keyframe points that model tracks at most (0 = all)");
  s.add("Dynamic.InitialPose.minimalSolver", &o.initial_pose.pnp.minimal_solver,
        {{"ap3p", geometry::PnpMinimalSolver::kAp3p}, {"epnp", geometry::PnpMinimalSolver::kEpnp}},
        "PnP RANSAC samples of models 1 and 2: ap3p = three points (AP3P), epnp = five points (EPnP, the paper's)");
  return s;
}

KeySection segmentationKeys(segmentation::SegmenterOptions& o) {
  KeySection s{"Segmentation"};
  s.add("Segmentation.backend", &o.backend, "segmenter backend, by the name it is registered under");
  s.add("Segmentation.modelsDir", &o.models_dir,
        "folder with the ONNX models; empty = found from `--models`, `$AMOS_MODELS`, `./models`, `../shared/models`")
      .formerly("Segmentation.models_dir");
  s.add("Segmentation.inputSize", &o.input_size, "side of the detector input: 320 or 416")
      .formerly("Segmentation.input_size");
  s.add("Segmentation.inputShape", &o.input_shape,
        "`square` (the frame letterboxed) or `frame` (the frame's aspect ratio)")
      .formerly("Segmentation.input_shape");
  s.add("Segmentation.maskInputSize", &o.mask_input_size,
        "side of the person crop the mask network sees (a multiple of 32 in [64, 256])")
      .formerly("Segmentation.mask_input_size");
  s.add("Segmentation.scoreThreshold", &o.score_threshold, "detector confidence at least")
      .formerly("Segmentation.score_threshold");
  s.add("Segmentation.nmsIou", &o.nms_iou, "overlap of the per-class non-maximum suppression")
      .formerly("Segmentation.nms_iou");
  s.add("Segmentation.classes", &o.classes, "COCO classes to mask: people get a learned mask, others box + depth");
  s.add("Segmentation.boxWidenX", &o.box_widen_x, "widening of a person crop, share of the box's width")
      .formerly("Segmentation.box_widen_x");
  s.add("Segmentation.boxWidenY", &o.box_widen_y, "... and of its height").formerly("Segmentation.box_widen_y");
  s.add("Segmentation.carriedBoxWidenX", &o.carried_box_widen_x,
        "growth of an earlier frame's person box masked again without the detector, share of its width");
  s.add("Segmentation.carriedBoxWidenY", &o.carried_box_widen_y, "... and of its height");
  s.add("Segmentation.maskThreshold", &o.mask_threshold, "person probability above which a pixel is masked")
      .formerly("Segmentation.mask_threshold");
  s.add("Segmentation.borderCropAspect", &o.border_crop_aspect,
        "a crop at the image border narrower than this times its height is extended beyond the border; 0 = off")
      .formerly("Segmentation.border_crop_aspect");
  s.add("Segmentation.minMaskFill", &o.min_mask_fill,
        "a person whose learned mask covers less of its box gets the box + depth mask; 0 = off")
      .formerly("Segmentation.min_mask_fill");
  s.add("Segmentation.depthTolerance", &o.depth_tolerance,
        "a box + depth mask holds the pixels this close to the object's median depth (m)")
      .formerly("Segmentation.depth_tolerance");
  s.add("Segmentation.maxInstances", &o.max_instances, "instances kept at most, highest score first")
      .formerly("Segmentation.max_instances");
  s.add("Segmentation.dilationSize", &o.dilation.size, "side of the dilation of the masks (odd px; 0 or 1 = none)")
      .formerly("Segmentation.dilation_size");
  s.add("Segmentation.dilationShape", &o.dilation.shape, "shape of that dilation: `ellipse`, `rect` or `cross`")
      .formerly("Segmentation.dilation_shape");
  s.add("Segmentation.threads", &o.threads, "OpenCV worker threads (process-wide); 0 = leave OpenCV's setting alone");
  return s;
}

}  // namespace amos::config
