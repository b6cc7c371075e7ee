#pragma once
// Stage 1 of the dynamic judgement for the geometric clusters (paper III-C, Eq. 5-6): the last frame's corner
// tracks become temporary map points (Eq. 6), are reprojected under the current frame's initial pose, and each
// decision cluster scores the Cauchy-robust mean of its tracks' errors (Eq. 5); clusters above the threshold are
// the potential motion regions (candidates). The tracks outside every potential motion region found so far
// (candidates, prior regions, the last frame's mask) are what the pose refit and the F fit are estimated on.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/front_end_types.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/reprojection_scoring.h"

namespace amos::dynamic {

// Where each track's last pixel lies in 3D: a world point from its trusted depth (Eq. 6), else, with
// Dynamic.Reprojection.intervalErrors, the interval of depths its LK window allows.
struct TrackPoints {
  std::vector<std::optional<Eigen::Vector3d>> points_w;  // per track (backProjectTracks)
  std::vector<std::optional<DepthInterval>> intervals;   // per track without a point; empty when intervals are off
};

TrackPoints liftTracks(const std::vector<PointTrack>& tracks, const cv::Mat& last_depth, const core::SE3& T_cw_last,
                       const core::PinholeCamera& camera, const DynamicOptions& options);

// Residuals under a pose T_cw (per track): from the back-projected point, else the interval's lower bound, else
// none.
std::vector<std::optional<Eigen::Vector2d>> residualsUnder(const TrackPoints& lifted,
                                                           const std::vector<PointTrack>& tracks,
                                                           const core::SE3& T_cw_last, const core::SE3& T_cw,
                                                           const core::PinholeCamera& camera);

struct CandidateScoring {
  TrackPoints lifted;
  std::vector<std::optional<double>> errors_px;  // per track, Eq. 5's ||e|| under the initial pose
  std::vector<int> cluster_of_track;             // decision cluster under each track's current pixel (-1: none)
  std::vector<ClusterScore> cluster_scores;      // Eq. 5 per cluster, initial pose
  // Tracks outside the candidate clusters and prior regions, and of those the ones that did not start in the last
  // frame's mask: what the fits use (outside_candidates), and what they fall back to (outside_now).
  std::vector<bool> outside_candidates, outside_now;
};

// tracks: last -> current. Fills
// diag.tracks_with_depth.
// Where the decisions are made: the decision map (CV_32S cluster per pixel, -1 outside), its number of clusters, and
// this frame's prior regions (empty when none are used).
struct DecisionClusters {
  const cv::Mat& decision_map;
  int count;
  const PriorRegions& prior;
};
CandidateScoring scoreCandidates(const std::vector<PointTrack>& tracks, const FrontEndInput& in,
                                 const DecisionClusters& clusters, const core::PinholeCamera& camera,
                                 const DynamicOptions& options, DynamicDiagnostics& diag);

}  // namespace amos::dynamic
