#pragma once
// The RGB-D sensor: turns the renderer's exact depth and colour into what a Kinect-class camera delivers.
// Depth: axial noise sigma(z) = a + b (z - c)^2 (Nguyen, Izadi, Lovell 2012: 0.0012 + 0.0019 (z - 0.4)^2),
// quantised to 1 / depth_factor metres, holes beyond the range limits, at depth discontinuities (the
// projector's shadow and mixed pixels), at grazing angles and a few at random. Colour: a little optical blur and
// per-channel Gaussian noise, rounded to 8 bits.
// Timing effects, each off by default and switchable alone (SensorOptions): the depth image taken at an offset
// from the colour image, and a rolling-shutter colour image (rows read out over a time). Optional: the depth
// steps of a structured-light sensor's disparity quantisation. The ground truth is always the camera pose at the
// colour image's time stamp (mid-exposure, the middle row's time under a rolling shutter).
#include <opencv2/core.hpp>
#include <vector>

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

// A structured-light sensor measures disparity d = f b / z in steps of 1 / subpixel pixel, so depth comes in
// steps of about z^2 / (f b subpixel): 2.87e-3 z^2 m for the Kinect v1 (b = 7.5 cm, f = 580 px, 1/8 px; Khoshelham
// and Elberink 2012). Applied after the depth noise, before the 1 / depth_factor rounding.
struct DisparityQuantisationOptions {
  bool enabled = false;
  double baseline_m = 0.075;  // projector-camera baseline
  double focal_px = 580;      // the infrared camera's focal length
  double subpixel = 8;        // disparity steps per pixel
  void check() const;
  // The depth whose disparity is the nearest step to z's (z > 0).
  double quantise(double z) const;
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
  DisparityQuantisationOptions disparity;
  ColorNoiseOptions color;
  bool motion_blur = false;  // average the colour over the exposure (depth and masks stay at mid-exposure)
  double exposure_s = 0.02;
  int motion_blur_samples = 5;
  // The depth image is taken at t + depth_time_offset_s (camera and movers at that time) and stamped so in
  // depth.txt, as in TUM / Bonn data, where depth stamps differ from colour stamps by up to ~15 ms. Less than half
  // a frame interval, so that the nearest stamp is still the same frame's.
  double depth_time_offset_s = 0;
  // Rolling shutter of the colour image: row r is exposed at t + (r / height - 0.5) * rolling_shutter_s
  // (0 = global shutter; 20-30 ms for a 30 Hz Kinect-class colour sensor). Rendered in bands of
  // rolling_shutter_band_rows rows, each at its middle row's time. The masks are the colour image's (rolling too);
  // depth stays a global-shutter image.
  double rolling_shutter_s = 0;
  int rolling_shutter_band_rows = 8;
  void check() const;
  // Any timing effect (depth offset, rolling shutter) on.
  bool timingEffects() const { return depth_time_offset_s != 0 || rolling_shutter_s > 0; }

  static core::CameraIntrinsics tumFr3Intrinsics();
};

// Standard deviation of the depth noise at depth z.
double depthSigma(const DepthNoiseOptions& options, double z);

// The colour image's row bands and their exposure times for a frame at time t: one band of the whole image at t
// without a rolling shutter.
struct ExposureBand {
  int begin = 0, end = 0;  // rows [begin, end)
  double t = 0;            // seconds
};
std::vector<ExposureBand> exposureBands(const SensorOptions& options, double t);

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
