#include "amos/config/dynamic_section.h"

namespace amos::config {

void readDynamicSection(YamlReader& in, dynamic::DynamicOptions& o) {
  std::string mode = dynamic::toString(o.mode);
  in.read("Dynamic.mode", mode);
  o.mode = dynamic::parseDynamicMode(mode);
  in.read("Dynamic.judgePriorRegions", o.judge_prior_regions);
  in.read("Dynamic.priorMaskedExtraction", o.prior_masked_extraction);
  in.read("Dynamic.priorMaskedExtractionCoverage", o.prior_masked_extraction_coverage);
  in.read("Dynamic.Prior.interval", o.prior.interval);
  in.read("Dynamic.Prior.lag", o.prior.lag);
  in.read("Dynamic.Prior.minTracks", o.prior.min_tracks);
  in.read("Dynamic.Prior.holdMissed", o.prior.hold_missed);
  in.read("Dynamic.Prior.auditPredictions", o.prior.audit_predictions);

  in.read("Dynamic.Superpixel.count", o.superpixel.num_superpixels);
  in.read("Dynamic.Superpixel.scale", o.superpixel.scale);
  in.read("Dynamic.Superpixel.colourScale", o.superpixel.colour_scale);
  in.read("Dynamic.Superpixel.depthScale", o.superpixel.depth_scale_m);
  in.read("Dynamic.Superpixel.iterations", o.superpixel.iterations);

  in.read("Dynamic.Cluster.count", o.cluster.num_clusters);
  in.read("Dynamic.Cluster.depthScale", o.cluster.depth_scale_m);
  in.read("Dynamic.Cluster.maxIterations", o.cluster.max_iterations);
  int cluster_seed = static_cast<int>(o.cluster.seed);
  in.read("Dynamic.Cluster.seed", cluster_seed);
  o.cluster.seed = static_cast<unsigned>(cluster_seed);

  in.read("Dynamic.Corners.maxCorners", o.tracking.max_corners);
  in.read("Dynamic.Corners.qualityLevel", o.tracking.quality_level);
  in.read("Dynamic.Corners.minDistance", o.tracking.min_distance_px);
  in.read("Dynamic.Corners.detectionScale", o.tracking.detection_scale);
  in.read("Dynamic.LK.window", o.tracking.lk_window);
  in.read("Dynamic.LK.pyramidLevels", o.tracking.lk_levels);
  in.read("Dynamic.LK.maxIterations", o.tracking.lk_max_iterations);
  in.read("Dynamic.LK.forwardBackwardThreshold", o.tracking.forward_backward_px);

  in.read("Dynamic.Reprojection.cauchyScale", o.reprojection.cauchy_scale_px);
  in.read("Dynamic.Reprojection.threshold", o.reprojection.candidate_threshold_px);
  in.read("Dynamic.Reprojection.minPoints", o.reprojection.min_points_per_cluster);
  in.read("Dynamic.Reprojection.maxDepth", o.reprojection.max_depth_m);
  in.read("Dynamic.Reprojection.depthEdgeRatio", o.reprojection.depth_edge_ratio);
  in.read("Dynamic.Reprojection.refitPose", o.reprojection.refit_pose);
  in.read("Dynamic.Reprojection.refitMinPoints", o.reprojection.refit_min_points);
  in.read("Dynamic.Reprojection.confirmSigmas", o.reprojection.confirm_sigmas);
  in.read("Dynamic.Reprojection.confirmThreshold", o.reprojection.confirm_threshold_px);
  in.read("Dynamic.Reprojection.intervalErrors", o.reprojection.interval_errors);

  in.read("Dynamic.Epipolar.ransacThreshold", o.epipolar.ransac_threshold_px);
  in.read("Dynamic.Epipolar.threshold", o.epipolar.dynamic_threshold_px);
  in.read("Dynamic.Epipolar.confidence", o.epipolar.confidence);
  in.read("Dynamic.Epipolar.minDynamicPoints", o.epipolar.min_dynamic_points);
  in.read("Dynamic.Epipolar.minFitPoints", o.epipolar.min_fit_points);
  in.read("Dynamic.Epipolar.seed", o.epipolar.seed);

  in.read("Dynamic.Boundary.radius", o.boundary.search_radius_px);
  in.read("Dynamic.Boundary.borderMargin", o.boundary.border_margin_px);
  in.read("Dynamic.Boundary.superpixelMask", o.boundary.superpixel_mask);
  in.read("Dynamic.Boundary.seedOutsideClusters", o.boundary.seed_outside_clusters);
  in.read("Dynamic.Temporal.excludeFromFits", o.temporal.exclude_last_mask_from_fits);

  in.read("Dynamic.InitialPose.inlierThreshold", o.initial_pose.inlier_threshold_px);
  in.read("Dynamic.InitialPose.keyframeForwardBackward", o.initial_pose.keyframe_forward_backward);
  in.read("Dynamic.InitialPose.keyframeMaxPoints", o.initial_pose.keyframe_max_points);
}

void readSegmentationSection(YamlReader& in, segmentation::SegmenterOptions& o) {
  in.read("Segmentation.backend", o.backend);
  in.read("Segmentation.models_dir", o.models_dir);
  in.read("Segmentation.input_size", o.input_size);
  in.read("Segmentation.input_shape", o.input_shape);
  in.read("Segmentation.mask_input_size", o.mask_input_size);
  in.read("Segmentation.score_threshold", o.score_threshold);
  in.read("Segmentation.nms_iou", o.nms_iou);
  in.read("Segmentation.classes", o.classes);
  in.read("Segmentation.box_widen_x", o.box_widen_x);
  in.read("Segmentation.box_widen_y", o.box_widen_y);
  in.read("Segmentation.mask_threshold", o.mask_threshold);
  in.read("Segmentation.border_crop_aspect", o.border_crop_aspect);
  in.read("Segmentation.min_mask_fill", o.min_mask_fill);
  in.read("Segmentation.depth_tolerance", o.depth_tolerance);
  in.read("Segmentation.max_instances", o.max_instances);
  in.read("Segmentation.dilation_size", o.dilation.size);
  in.read("Segmentation.dilation_shape", o.dilation.shape);
  in.read("Segmentation.threads", o.threads);
}

}  // namespace amos::config
