#pragma once
// The pose again, without the potential motion regions (ReprojectionOptions::refit_pose), and every cluster scored
// under it (paper III-C, Eq. 5, as the paper refits F without its violators). The epipolar test is blind to motion
// along the epipolar lines; the depth-based error is not, once the pose error it was guarding against is removed:
// a cluster whose error stays high under the refitted pose is confirmed dynamic.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/candidate_scoring.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/front_end_types.h"
#include "amos/dynamic/reprojection_scoring.h"

namespace amos::dynamic {

struct PoseConfirmation {
  PoseRefit refit;  // T_cw: the refitted pose, else the initial one
  std::vector<std::optional<Eigen::Vector2d>> residuals;  // per track under refit.T_cw (points, else intervals)
  std::vector<ClusterScore> confirm_scores;  // Eq. 5 per cluster under the refitted pose (empty without a refit)
  std::vector<bool> confirmed;               // per cluster: refit ok and above the confirmation threshold
  // The residual a static track stays below: the confirmation threshold after a refit, else the candidate one.
  double static_bar_px = 0;
  // The tracks the fits use: CandidateScoring::outside_candidates, or outside_now when those left the refit too few.
  std::vector<bool> fit_tracks;
};

// Fills diag.pose_refit_*, confirm_threshold_px and candidate_clusters (above threshold under the initial or the
// refitted pose).
PoseConfirmation confirmUnderRefittedPose(const std::vector<PointTrack>& tracks, const CandidateScoring& candidates,
                                          const core::SE3& T_cw_last, const core::SE3& T_cw_initial,
                                          const core::PinholeCamera& camera, const ReprojectionOptions& options,
                                          DynamicDiagnostics& diag);

}  // namespace amos::dynamic
