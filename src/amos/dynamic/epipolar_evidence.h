#pragma once
// Stage 2 of the dynamic judgement (paper III-C, Eq. 7-8): a fundamental matrix fitted on the undistorted tracks
// outside the potential motion regions, the distance of every track from its epipolar line, and the tracks beyond
// the epipolar threshold (the violators, which vote in cluster_voting.h).
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/front_end_types.h"
#include "amos/dynamic/epipolar_check.h"

namespace amos::dynamic {

struct EpipolarEvidence {
  FundamentalFit fit;
  std::vector<double> distance_px;     // per track (infinity when there was no F)
  std::vector<cv::Point2f> violators;  // current (raw) pixels of the tracks beyond the threshold; none without F
};

// fit_tracks: per track, whether F may be fitted on it (PoseConfirmation::fit_tracks). Fills diag.f_*,
// fundamental_ok and dynamic_points.
EpipolarEvidence fitEpipolarEvidence(const std::vector<PointTrack>& tracks, const std::vector<bool>& fit_tracks,
                                     const core::PinholeCamera& camera, const EpipolarOptions& options,
                                     DynamicDiagnostics& diag);

}  // namespace amos::dynamic
