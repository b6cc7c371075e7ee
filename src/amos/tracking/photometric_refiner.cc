#include "amos/tracking/photometric_refiner.h"

#include "amos/core/error.h"
#include "amos/map/map_point.h"
#include "amos/match/pose_from_matches.h"

namespace amos::tracking {

PhotometricRefiner::PhotometricRefiner(const core::PinholeCamera& camera, const geometry::PhotometricOptions& options)
    : options_(options), lens_(camera.intrinsics().lens()) {
  options_.check();
  projection_ = {camera.fx(), camera.fy(), camera.cx(), camera.cy(), 0};
}

// The frame's raw grey image and dynamic mask as the camera and the segmenter delivered them: the refinement
// samples them through the lens model, so nothing is undistorted here.
const geometry::PhotometricImage& PhotometricRefiner::imageOf(const map::Frame& frame) {
  if (image_frame_ != frame.id) {
    core::require(!frame.gray.empty(), "PhotometricRefiner: frame without its grey image");
    geometry::makePhotometricImage(frame.gray, frame.dynamic_mask, projection_, lens_, options_, image_);
    image_frame_ = frame.id;
  }
  return image_;
}

PhotometricRefinementStats PhotometricRefiner::refine(map::Frame& frame, map::KeyFrameId reference,
                                                      const core::SE3& T_rw) {
  PhotometricRefinementStats stats;
  const auto found = templates_.find(reference);
  if (found == templates_.end()) return stats;
  std::vector<geometry::PoseObservation> inliers;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.map_points[i] && !frame.outlier[i]) inliers.push_back(match::poseObservationOf(frame, i));
  }
  geometry::PhotometricProblem problem;
  problem.features = &inliers;
  problem.projection = frame.sensor->projection();
  problem.reference = found->second.get();
  problem.T_rw = T_rw;
  problem.current = &imageOf(frame);
  const geometry::PhotometricResult result = geometry::refinePosePhotometrically(problem, frame.T_cw, options_);
  stats.attempted = true;
  stats.accepted = result.accepted;
  stats.points = result.points;
  stats.sigma = result.sigma;
  if (result.accepted) {
    frame.setPose(result.T_cw);
    stats.information = result.information;
  }
  return stats;
}

void PhotometricRefiner::addKeyFrame(map::KeyFrameId id, const map::Frame& frame) {
  if (frame.gray.empty() || frame.depth_image.empty()) return;
  const geometry::PhotometricImage& image = imageOf(frame);
  templates_[id] = std::make_shared<const geometry::PhotometricTemplate>(
      geometry::makePhotometricTemplate(image, frame.depth_image, options_));
}

}  // namespace amos::tracking
