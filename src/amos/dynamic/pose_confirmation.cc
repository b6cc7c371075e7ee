#include "amos/dynamic/pose_confirmation.h"

namespace amos::dynamic {

PoseConfirmation confirmUnderRefittedPose(const std::vector<PointTrack>& tracks, const CandidateScoring& candidates,
                                          const core::SE3& T_cw_last, const core::SE3& T_cw_initial,
                                          const core::PinholeCamera& camera, const ReprojectionOptions& options,
                                          DynamicDiagnostics& diag) {
  PoseConfirmation confirmation;
  const std::vector<std::optional<Eigen::Vector3d>>& points_w = candidates.lifted.points_w;
  // When the last mask leaves too few tracks (it covered most of the view), the refit does without it.
  confirmation.fit_tracks = candidates.outside_candidates;
  PoseRefit& refit = confirmation.refit;
  refit.T_cw = T_cw_initial;
  if (options.refit_pose) {
    refit = refitPose(tracks, points_w, confirmation.fit_tracks, T_cw_initial, camera, options);
    if (!refit.ok && candidates.outside_now != confirmation.fit_tracks) {
      confirmation.fit_tracks = candidates.outside_now;
      refit = refitPose(tracks, points_w, confirmation.fit_tracks, T_cw_initial, camera, options);
    }
  }
  diag.pose_refit_ok = refit.ok;
  diag.pose_refit_points = refit.points;
  diag.pose_refit_inliers = refit.inliers;
  diag.pose_refit_sigma_px = refit.sigma_px;
  confirmation.residuals = residualsUnder(candidates.lifted, tracks, T_cw_last, refit.T_cw, camera);
  confirmation.static_bar_px = options.candidate_threshold_px;
  const int num_clusters = static_cast<int>(candidates.cluster_scores.size());
  confirmation.confirmed.assign(num_clusters, false);
  if (refit.ok) {
    ReprojectionOptions confirm = options;
    confirm.candidate_threshold_px = confirmThreshold(refit, options);
    diag.confirm_threshold_px = confirm.candidate_threshold_px;
    confirmation.static_bar_px = confirm.candidate_threshold_px;
    confirmation.confirm_scores =
        scoreClusters(residualNorms(confirmation.residuals), candidates.cluster_of_track, num_clusters, confirm);
    for (int c = 0; c < num_clusters; ++c) confirmation.confirmed[c] = confirmation.confirm_scores[c].candidate;
  }
  diag.candidate_clusters = 0;
  for (int c = 0; c < num_clusters; ++c)
    if (candidates.cluster_scores[c].candidate || confirmation.confirmed[c]) ++diag.candidate_clusters;
  return confirmation;
}

}  // namespace amos::dynamic
