#pragma once
// What every frame of a run shares: the calibrated camera, the virtual stereo baseline of RGB-D tracking and
// the scale pyramid of the ORB extractor. Immutable after construction; frames hold it by shared_ptr.
#include <opencv2/core.hpp>

#include <vector>

#include "amos/core/camera.h"
#include "amos/feature/orb_extractor.h"
#include "amos/geometry/pose_optimizer.h"

namespace amos::map {

struct SensorOptions {
  double bf = 40.0;        // Camera.bf: baseline (m) x fx of the virtual stereo pair
  double th_depth = 40.0;  // ThDepth: keypoints closer than th_depth * bf / fx metres are "close"
  void check() const;
};

class Sensor {
 public:
  Sensor(const core::CameraIntrinsics& intrinsics, const SensorOptions& options, const feature::OrbOptions& orb);

  const core::PinholeCamera& camera() const { return camera_; }
  double bf() const { return bf_; }
  double baseline() const { return bf_ / camera_.fx(); }
  double closeDepth() const { return close_depth_; }  // metres
  geometry::StereoProjection projection() const { return {camera_.fx(), camera_.fy(), camera_.cx(), camera_.cy(), bf_}; }

  int numLevels() const { return static_cast<int>(scale_.size()); }
  float scaleFactor() const { return scale_factor_; }
  float logScaleFactor() const { return log_scale_factor_; }
  const std::vector<float>& scales() const { return scale_; }
  const std::vector<float>& sigma2() const { return sigma2_; }
  const std::vector<float>& invSigma2() const { return inv_sigma2_; }

  // Undistorted image bounds (where undistorted keypoints and projections may fall).
  double minU() const { return bounds_.x; }
  double maxU() const { return bounds_.x + bounds_.width; }
  double minV() const { return bounds_.y; }
  double maxV() const { return bounds_.y + bounds_.height; }
  bool inBounds(double u, double v) const { return u >= minU() && u < maxU() && v >= minV() && v < maxV(); }

 private:
  core::PinholeCamera camera_;
  double bf_ = 0, close_depth_ = 0;
  float scale_factor_ = 1.2f, log_scale_factor_ = 0;
  std::vector<float> scale_, sigma2_, inv_sigma2_;
  cv::Rect2d bounds_;
};

}  // namespace amos::map
