#include "amos/dynamic/candidate_scoring.h"

namespace amos::dynamic {

TrackPoints liftTracks(const std::vector<PointTrack>& tracks, const cv::Mat& last_depth, const core::SE3& T_cw_last,
                       const core::PinholeCamera& camera, const DynamicOptions& options) {
  TrackPoints lifted;
  lifted.points_w = backProjectTracks(tracks, last_depth, T_cw_last, camera, options.reprojection);
  // Tracks without a trusted depth (on a depth edge, among holes) are where the corners of a mover's outline are,
  // and on a person with dark clothes nearly all of them: each gets the smallest error any depth of its
  // neighbourhood allows (intervalResiduals), a lower bound that a static point under the right pose keeps near 0.
  if (options.reprojection.interval_errors) {
    lifted.intervals = trackDepthIntervals(tracks, last_depth, options.tracking.lk_window / 2, options.reprojection);
    for (std::size_t i = 0; i < lifted.intervals.size(); ++i)
      if (lifted.points_w[i]) lifted.intervals[i].reset();
  }
  return lifted;
}

std::vector<std::optional<Eigen::Vector2d>> residualsUnder(const TrackPoints& lifted,
                                                           const std::vector<PointTrack>& tracks,
                                                           const core::SE3& T_cw_last, const core::SE3& T_cw,
                                                           const core::PinholeCamera& camera) {
  auto residuals = reprojectionResiduals(tracks, lifted.points_w, T_cw, camera);
  if (lifted.intervals.empty()) return residuals;
  const auto lower = intervalResiduals(tracks, lifted.intervals, T_cw_last, T_cw, camera);
  for (std::size_t i = 0; i < residuals.size(); ++i)
    if (!residuals[i]) residuals[i] = lower[i];
  return residuals;
}

CandidateScoring scoreCandidates(const std::vector<PointTrack>& tracks, const FrontEndInput& in,
                                 const DecisionClusters& clusters, const core::PinholeCamera& camera,
                                 const DynamicOptions& options, DynamicDiagnostics& diag) {
  const cv::Mat& decision_map = clusters.decision_map;
  const int num_clusters = clusters.count;
  const PriorRegions& prior = clusters.prior;
  CandidateScoring scoring;
  scoring.lifted = liftTracks(tracks, in.last_depth, in.T_cw_last, camera, options);
  scoring.errors_px = residualNorms(residualsUnder(scoring.lifted, tracks, in.T_cw_last, in.T_cw_initial, camera));
  scoring.cluster_of_track.resize(tracks.size());
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    scoring.cluster_of_track[i] = labelAt(decision_map, tracks[i].current);
    if (scoring.errors_px[i]) ++diag.tracks_with_depth;
  }
  scoring.cluster_scores = scoreClusters(scoring.errors_px, scoring.cluster_of_track, num_clusters,
                                         options.reprojection);

  // Temporal evidence: the tracks that start inside the last frame's final mask were on a mover one frame ago, and
  // movers rarely stop between two frames (33 ms). They are kept out of the fits below like the candidates: an
  // undetected person holding a fifth of the tracks would otherwise pull the initial pose and the refit half-way
  // to its own motion (a person moving 3 px per frame leaves both sides within the refit's inlier band), and then
  // nothing in the frame looks dynamic. Only the fits lose them; every decision below is still made from this
  // frame's evidence, so a static surface wrongly masked in the last frame is released here (its tracks fit the
  // clean pose) instead of staying masked for good.
  std::vector<bool> from_last_mask(tracks.size(), false);
  if (options.temporal.exclude_last_mask_from_fits && !in.last_mask.empty())
    for (std::size_t i = 0; i < tracks.size(); ++i) from_last_mask[i] = maskAt(in.last_mask, tracks[i].last);

  // Tracks outside the potential motion regions found so far (candidate clusters, prior regions, the last mask):
  // what F and the pose refit are estimated on.
  scoring.outside_candidates.assign(tracks.size(), false);
  scoring.outside_now.assign(tracks.size(), false);
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const int c = scoring.cluster_of_track[i];
    if (c >= 0 && scoring.cluster_scores[c].candidate) continue;
    if (labelAt(prior.components, tracks[i].current) > 0) continue;
    scoring.outside_now[i] = true;
    scoring.outside_candidates[i] = !from_last_mask[i];
  }
  return scoring;
}

}  // namespace amos::dynamic
