#pragma once
// The RGB-D sensor: turns the renderer's exact depth and colour into what a Kinect-class camera delivers.
// Depth: axial noise sigma(z) = a + b (z - c)^2 (Nguyen, Izadi, Lovell 2012: 0.0012 + 0.0019 (z - 0.4)^2),
// quantised to 1 / depth_factor metres, holes beyond the range limits, at depth discontinuities (the
// projector's shadow and mixed pixels), at grazing angles and a few at random. Colour: a little optical blur and
// per-channel Gaussian noise, rounded to 8 bits.
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/synth/random.h"

namespace amos::synth {

struct DepthNoiseOptions {
  bool enabled = true;              // false: exact depth, only quantised (and range-limited)
  double sigma_base_m = 0.0012;     // sigma(z) = sigma_base_m + sigma_quadratic * (z - sigma_offset_m)^2
  double sigma_quadratic = 0.0019;  // per metre
  double sigma_offset_m = 0.4;
  double min_range_m = 0.4;               // closer than this: no reading
  double max_range_m = 5.0;               // farther than this: no reading
  double edge_jump_m = 0.04;              // neighbours differing by more than edge_jump_m + edge_jump_relative * z
  double edge_jump_relative = 0.03;       //   mark a depth edge
  double edge_hole_probability = 0.75;    // an edge pixel loses its reading
  double edge_band_probability = 0.3;     // a pixel next to an edge pixel loses its reading
  double grazing_cos = 0.1;               // surfaces seen at |cos| below this ...
  double grazing_hole_probability = 0.7;  // ... lose their reading with this probability
  double dropout_probability = 0.002;     // isolated missing pixels anywhere
  double depth_factor = 5000;             // stored value = metres * depth_factor (TUM)
  void check() const;
};

struct ColorNoiseOptions {
  bool enabled = true;
  double sigma = 2.0;          // per-channel Gaussian noise, 8-bit levels
  double blur_sigma_px = 0.5;  // optical blur before the noise (0 = none)
  void check() const;
};

struct SensorOptions {
  core::CameraIntrinsics intrinsics = tumFr3Intrinsics();
  double fps = 30;
  DepthNoiseOptions depth;
  ColorNoiseOptions color;
  bool motion_blur = false;  // average the colour over the exposure (depth and masks stay at mid-exposure)
  double exposure_s = 0.02;
  int motion_blur_samples = 5;
  void check() const;

  static core::CameraIntrinsics tumFr3Intrinsics();
};

// Standard deviation of the depth noise at depth z.
double depthSigma(const DepthNoiseOptions& options, double z);

class SensorModel {
 public:
  explicit SensorModel(const SensorOptions& options);

  // Exact depth (CV_32F metres, 0 = nothing) and |cos| incidence -> the 16-bit depth image (0 = no reading).
  cv::Mat measureDepth(const cv::Mat& exact_depth, const cv::Mat& incidence, Random& rng) const;
  // Rendered colour (CV_32FC3, 0..255) -> 8-bit BGR.
  cv::Mat measureColor(const cv::Mat& color, Random& rng) const;

  const SensorOptions& options() const { return options_; }

 private:
  SensorOptions options_;
  GaussianTable gaussian_;
};

}  // namespace amos::synth
