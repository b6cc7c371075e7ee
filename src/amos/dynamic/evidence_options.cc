#include "amos/dynamic/evidence_options.h"

#include "amos/core/option_error.h"

namespace amos::dynamic {

void DepthEvidenceOptions::check() const {
  core::requireInRange(sample_step_px, "sample_step_px", 1, 32);
  core::requirePositive(noise_base_m, "noise_base_m");
  core::requireAtLeast(noise_quadratic, "noise_quadratic", 0.0);
  core::requireAtLeast(noise_offset_m, "noise_offset_m", 0.0);
  core::requirePositive(sigmas, "sigmas");
  core::requireAtLeast(min_residual_m, "min_residual_m", 0.0);
  core::requirePositive(max_depth_m, "max_depth_m");
  core::requireInRange(min_relative_residual, "min_relative_residual", 0.0, 1.0);
  core::requireAtLeast(min_samples, "min_samples", 1);
  core::requireInRange(cluster_share, "cluster_share", 1e-6, 1.0);
  core::requirePositive(violation_sigmas, "violation_sigmas");
  core::requireInRange(violation_share, "violation_share", 1e-6, 1.0);
  core::requireAtLeast(min_violations, "min_violations", 1);
  core::requireAtLeast(unscored_cluster_superpixels, "unscored_cluster_superpixels", 1);
  core::requireAtLeast(baseline_frames, "baseline_frames", 0);
  core::requireInRange(baseline_relative_residual, "baseline_relative_residual", 0.0, 1.0);
}

void BaselineTrackOptions::check() const {
  core::requirePositive(sigmas, "sigmas");
  core::requireAtLeast(min_motion_px, "min_motion_px", 0.0);
  core::requireAtLeast(min_votes, "min_votes", 1);
  core::requireInRange(cluster_share, "cluster_share", 1e-6, 1.0);
  core::requireAtLeast(grow_dissimilarity, "grow_dissimilarity", 0.0);
}

void RigidMoverOptions::check() const {
  core::requireAtLeast(min_inliers, "min_inliers", 6);
  core::requirePositive(inlier_px, "inlier_px");
  core::requireAtLeast(max_movers, "max_movers", 1);
  core::requireAtLeast(sample_step_px, "sample_step_px", 1);
  core::requireAtLeast(min_separation_px, "min_separation_px", 0.0);
  core::requireAtLeast(intensity_margin, "intensity_margin", 0.0);
  core::requireAtLeast(min_samples, "min_samples", 1);
  core::requireAtLeast(region_reach_px, "region_reach_px", 0);
  core::requireAtLeast(min_gradient, "min_gradient", 0.0);
}

}  // namespace amos::dynamic
