#include "amos/dynamic/epipolar_evidence.h"

#include <limits>

namespace amos::dynamic {

EpipolarEvidence fitEpipolarEvidence(const std::vector<PointTrack>& tracks, const std::vector<bool>& fit_tracks,
                                     const core::PinholeCamera& camera, const EpipolarOptions& options,
                                     DynamicDiagnostics& diag) {
  EpipolarEvidence evidence;
  std::vector<cv::Point2f> last_raw, current_raw;
  for (const PointTrack& t : tracks) last_raw.push_back(t.last), current_raw.push_back(t.current);
  const std::vector<cv::Point2f> last_u = camera.undistort(last_raw), current_u = camera.undistort(current_raw);
  // F is fitted on the tracks outside the potential motion regions: a rigid moving object holding many tracks
  // would otherwise pull F towards its own motion whenever the static scene has little parallax (small baseline,
  // one dominant plane), and then it would satisfy the epipolar test. With too few such tracks (e.g. every
  // cluster a candidate after a bad initial pose) all tracks are used.
  std::vector<cv::Point2f> fit_last, fit_current;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (!fit_tracks[i]) continue;
    fit_last.push_back(last_u[i]);
    fit_current.push_back(current_u[i]);
  }
  if (static_cast<int>(fit_last.size()) < options.min_fit_points) fit_last = last_u, fit_current = current_u;
  diag.f_fit_points = static_cast<int>(fit_last.size());
  evidence.fit = fitFundamental(fit_last, fit_current, options);
  const FundamentalFit& fit = evidence.fit;
  diag.fundamental_ok = fit.ok;
  diag.f_ransac_inliers = fit.ransac_inliers;
  diag.f_refit_points = fit.refit_points;
  diag.f_final_inliers = fit.final_inliers;
  evidence.distance_px.assign(tracks.size(), std::numeric_limits<double>::infinity());
  if (!fit.ok) return evidence;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    evidence.distance_px[i] = epipolarDistance(fit.F, {last_u[i].x, last_u[i].y}, {current_u[i].x, current_u[i].y});
    if (evidence.distance_px[i] > options.dynamic_threshold_px) evidence.violators.push_back(tracks[i].current);
  }
  diag.dynamic_points = static_cast<int>(evidence.violators.size());
  return evidence;
}

}  // namespace amos::dynamic
