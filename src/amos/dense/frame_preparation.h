#pragma once
// What of a frame is fused: the depth readings in range that are neither dynamic (the front end's mask grown by
// Dense.maskMargin) nor on a depth discontinuity (Dense.edgeJump, Dense.edgeMargin), undistorted when the camera
// has lens distortion and scaled to Dense.scale. The dynamic readings left out are kept apart (removed_points.ply).
// Pure image work (OpenCV), no state but the undistortion maps made once.
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/dense/dense_options.h"

namespace amos::dense {

struct FrameImages {
  cv::Mat depth;         // CV_32F metres, 0 = no reading
  cv::Mat bgr;           // CV_8UC3
  cv::Mat dynamic_mask;  // CV_8U, non-zero = dynamic; empty = nothing dynamic (mode none)
};

struct PreparedFrame {
  cv::Mat depth;    // CV_32F metres at Dense.scale: the static readings to fuse, 0 elsewhere
  cv::Mat removed;  // CV_32F metres at Dense.scale: the dynamic readings left out, 0 elsewhere
  cv::Mat bgr;      // CV_8UC3 at Dense.scale
};

// The intrinsics of an image resized by `scale` (pixel centres kept: c' = (c + 0.5) s - 0.5), without distortion.
core::CameraIntrinsics scaledIntrinsics(const core::CameraIntrinsics& camera, double scale);

// Pixels whose 3x3 neighbourhood spans a depth step above edge_jump x depth (or touches a missing reading), grown
// by edge_margin_px: CV_8U, 255 = depth edge.
cv::Mat depthEdges(const cv::Mat& depth, double edge_jump, int edge_margin_px);

class FramePreparer {
 public:
  FramePreparer(const core::CameraIntrinsics& camera, const DenseOptions& options);
  // Throws core::Error when the images do not have the camera's size or type.
  PreparedFrame prepare(const FrameImages& frame) const;
  // The intrinsics of the prepared images.
  const core::CameraIntrinsics& intrinsics() const { return scaled_; }

 private:
  core::CameraIntrinsics camera_, scaled_;
  DenseOptions options_;
  cv::Mat map_x_, map_y_;  // undistortion maps (empty without distortion)
};

}  // namespace amos::dense
