#include "amos/match/pose_from_matches.h"

namespace amos::match {

geometry::PoseObservation poseObservationOf(const map::Frame& frame, std::size_t i) {
  const map::FrameFeatures& f = *frame.features;
  geometry::PoseObservation o;
  o.point_w = frame.map_points[i]->position();
  o.pixel = {f.keys[i].pt.x, f.keys[i].pt.y};
  o.u_right = f.u_right[i];
  o.inv_sigma2 = frame.sensor->invSigma2()[f.keys[i].octave];
  return o;
}

int optimizeFramePose(map::Frame& frame, const geometry::PoseOptimizerOptions& options) {
  std::vector<geometry::PoseObservation> obs;
  std::vector<int> index;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (!frame.map_points[i]) continue;
    obs.push_back(poseObservationOf(frame, i));
    index.push_back(static_cast<int>(i));
  }
  frame.outlier.assign(frame.size(), false);
  if (obs.size() < 3) return 0;
  const auto result = geometry::optimizePose(obs, frame.T_cw, frame.sensor->projection(), options);
  frame.setPose(result.T_cw);
  for (std::size_t k = 0; k < index.size(); ++k) frame.outlier[index[k]] = result.outlier[k];
  return result.num_inliers;
}

int optimizeFramePoseDroppingOutliers(map::Frame& frame, const geometry::PoseOptimizerOptions& options) {
  const int inliers = optimizeFramePose(frame, options);
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.outlier[i]) {
      frame.map_points[i].reset();
      frame.outlier[i] = false;
    }
  }
  return inliers;
}

int poseFromMatchesByPnp(map::Frame& frame, const std::vector<map::MapPointPtr>& matches,
                         const geometry::PnpRansacOptions& options) {
  const map::FrameFeatures& f = *frame.features;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<int> index;
  for (std::size_t i = 0; i < matches.size(); ++i) {
    if (!matches[i]) continue;
    points.push_back(matches[i]->position());
    pixels.emplace_back(f.keys[i].pt.x, f.keys[i].pt.y);
    index.push_back(static_cast<int>(i));
  }
  const geometry::PnpResult pnp = geometry::solvePnpRansac(points, pixels, frame.sensor->camera(), options);
  if (!pnp.success) return 0;
  frame.resetMatches();
  frame.setPose(pnp.T_cw);
  for (const int k : pnp.inliers) frame.map_points[index[k]] = matches[index[k]];
  return static_cast<int>(pnp.inliers.size());
}

}  // namespace amos::match
