#pragma once
// Tracking's side of the photometric refinement (geometry/photometric_alignment.h): keeps a template of every
// keyframe tracking made (its selected pixels with depth, from the raw grey image outside the dynamic mask), and
// refines each tracked frame's pose against its reference keyframe's template jointly with the frame's
// feature inliers. The frame's pose is stored relative to that keyframe (T_cr), so the refinement tightens exactly
// the relation the output trajectory keeps.
//
// Keyframes loaded from a map file have no template (their images are not saved): frames referring to them keep
// the feature pose. Used from the tracking thread only.
#include <memory>
#include <optional>
#include <unordered_map>

#include "amos/core/camera.h"
#include "amos/geometry/photometric_alignment.h"
#include "amos/map/frame.h"
#include "amos/map/ids.h"

namespace amos::tracking {

struct PhotometricRefinementStats {
  bool attempted = false, accepted = false;
  int points = 0;
  double sigma = 0;
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();  // the pixels' alone (accepted)
};

class PhotometricRefiner {
 public:
  PhotometricRefiner(const core::PinholeCamera& camera, const geometry::PhotometricOptions& options);

  // Refines frame.T_cw against the template of keyframe `reference` (pose T_rw) with the frame's inlier matches
  // (map points not flagged outlier). Does nothing without a template.
  PhotometricRefinementStats refine(map::Frame& frame, map::KeyFrameId reference, const core::SE3& T_rw);
  // Makes keyframe `id`'s template from `frame` (the frame it was made from).
  void addKeyFrame(map::KeyFrameId id, const map::Frame& frame);

 private:
  const geometry::PhotometricImage& imageOf(const map::Frame& frame);

  geometry::PhotometricOptions options_;
  geometry::StereoProjection projection_;
  core::RadialTangential lens_;
  std::unordered_map<map::KeyFrameId, std::shared_ptr<const geometry::PhotometricTemplate>> templates_;
  std::optional<map::FrameId> image_frame_;  // the frame image_ was made from
  geometry::PhotometricImage image_;         // its buffers are reused from frame to frame
};

}  // namespace amos::tracking
