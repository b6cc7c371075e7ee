#include "amos/synth/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::synth {

void DepthNoiseOptions::check() const {
  core::require(sigma_base_m >= 0 && sigma_quadratic >= 0,
                "synth.sensor.depth.sigma_base_m / sigma_quadratic must be >= 0");
  core::require(min_range_m >= 0 && max_range_m > min_range_m,
                "synth.sensor.depth.max_range_m must exceed min_range_m");
  core::require(max_range_m * depth_factor < 65535, "synth.sensor.depth.max_range_m * depth_factor must fit 16 bits");
  core::require(depth_factor > 0, "synth.sensor.depth.depth_factor must be > 0");
  for (double p : {edge_hole_probability, edge_band_probability, grazing_hole_probability, dropout_probability})
    core::require(p >= 0 && p <= 1, "synth.sensor.depth.*_probability must be in [0, 1]");
  core::require(edge_jump_m > 0 && edge_jump_relative >= 0, "synth.sensor.depth.edge_jump_m must be > 0");
}

void DisparityQuantisationOptions::check() const {
  core::require(baseline_m > 0 && focal_px > 0 && subpixel > 0,
                "synth.sensor.disparity.baseline_m, focal_px and subpixel must be > 0");
}

double DisparityQuantisationOptions::quantise(double z) const {
  const double fb = focal_px * baseline_m;
  const double steps = std::max(1.0, std::round(fb / z * subpixel));
  return fb * subpixel / steps;
}

void ColorNoiseOptions::check() const {
  core::require(sigma >= 0, "synth.sensor.color.sigma must be >= 0");
  core::require(blur_sigma_px >= 0 && blur_sigma_px < 5, "synth.sensor.color.blur_sigma_px must be in [0, 5)");
}

void SensorOptions::check() const {
  intrinsics.check();
  core::require(fps > 0 && fps <= 1000, "synth.sensor.fps must be in (0, 1000]");
  core::require(exposure_s >= 0 && exposure_s < 1 / fps, "synth.sensor.exposure_s must be in [0, 1 / fps)");
  core::require(motion_blur_samples >= 1 && motion_blur_samples <= 64,
                "synth.sensor.motion_blur_samples must be in [1, 64]");
  core::require(std::abs(depth_time_offset_s) < 0.5 / fps,
                "synth.sensor.depth_time_offset_s must be below half a frame interval (0.5 / fps) in magnitude");
  core::require(rolling_shutter_s >= 0 && rolling_shutter_s <= 1 / fps,
                "synth.sensor.rolling_shutter_s must be in [0, 1 / fps]");
  core::require(rolling_shutter_band_rows >= 1 && rolling_shutter_band_rows <= intrinsics.height,
                "synth.sensor.rolling_shutter_band_rows must be in [1, image height]");
  depth.check();
  disparity.check();
  color.check();
}

std::vector<ExposureBand> exposureBands(const SensorOptions& o, double t) {
  const int H = o.intrinsics.height;
  if (o.rolling_shutter_s <= 0) return {{0, H, t}};
  std::vector<ExposureBand> bands;
  for (int begin = 0; begin < H; begin += o.rolling_shutter_band_rows) {
    const int end = std::min(H, begin + o.rolling_shutter_band_rows);
    const double middle_row = 0.5 * (begin + end - 1);
    bands.push_back({begin, end, t + (middle_row / H - 0.5) * o.rolling_shutter_s});
  }
  return bands;
}

core::CameraIntrinsics SensorOptions::tumFr3Intrinsics() {
  core::CameraIntrinsics k;
  k.fx = 535.4;
  k.fy = 539.2;
  k.cx = 320.1;
  k.cy = 247.6;
  k.width = 640;
  k.height = 480;
  return k;
}

double depthSigma(const DepthNoiseOptions& o, double z) {
  const double d = z - o.sigma_offset_m;
  return o.sigma_base_m + o.sigma_quadratic * d * d;
}

SensorModel::SensorModel(const SensorOptions& options) : options_(options) { options_.check(); }

cv::Mat SensorModel::measureDepth(const cv::Mat& exact, const cv::Mat& incidence, Random& rng) const {
  const DepthNoiseOptions& o = options_.depth;
  const int W = exact.cols, H = exact.rows;
  cv::Mat out(H, W, CV_16U, cv::Scalar(0));
  // Depth edges from the exact depth (4-neighbourhood).
  cv::Mat edge(H, W, CV_8U, cv::Scalar(0));
  if (o.enabled) {
    for (int y = 0; y < H; ++y) {
      const float* z = exact.ptr<float>(y);
      const float* zd = y + 1 < H ? exact.ptr<float>(y + 1) : nullptr;
      uchar* e = edge.ptr<uchar>(y);
      uchar* ed = y + 1 < H ? edge.ptr<uchar>(y + 1) : nullptr;
      for (int x = 0; x < W; ++x) {
        const double limit = o.edge_jump_m + o.edge_jump_relative * z[x];
        if (x + 1 < W && std::abs(z[x + 1] - z[x]) > limit) e[x] = e[x + 1] = 1;
        if (zd && std::abs(zd[x] - z[x]) > limit) e[x] = ed[x] = 1;
      }
    }
  }
  for (int y = 0; y < H; ++y) {
    const float* z = exact.ptr<float>(y);
    const float* c = incidence.ptr<float>(y);
    std::uint16_t* d = out.ptr<std::uint16_t>(y);
    for (int x = 0; x < W; ++x) {
      const double zt = z[x];
      if (!(zt > o.min_range_m) || zt > o.max_range_m) continue;
      double zm = zt;
      if (o.enabled) {
        const std::uint32_t bits = rng.bits();
        const double u = (bits >> 16) * (1.0 / 65536.0);  // hole decisions
        const bool near_edge = (x > 0 && edge.at<uchar>(y, x - 1)) || (x + 1 < W && edge.at<uchar>(y, x + 1)) ||
                               (y > 0 && edge.at<uchar>(y - 1, x)) || (y + 1 < H && edge.at<uchar>(y + 1, x));
        if (edge.at<uchar>(y, x) && u < o.edge_hole_probability) continue;
        if (!edge.at<uchar>(y, x) && near_edge && u < o.edge_band_probability) continue;
        if (c[x] < o.grazing_cos && u < o.grazing_hole_probability) continue;
        if (u > 1 - o.dropout_probability) continue;
        zm = zt + depthSigma(o, zt) * gaussian_[bits];
      }
      if (options_.disparity.enabled && zm > 0) zm = options_.disparity.quantise(zm);
      const long v = std::lround(zm * o.depth_factor);
      if (v > 0 && v < 65536) d[x] = static_cast<std::uint16_t>(v);
    }
  }
  return out;
}

cv::Mat SensorModel::measureColor(const cv::Mat& color, Random& rng) const {
  const ColorNoiseOptions& o = options_.color;
  cv::Mat blurred = color;
  if (o.enabled && o.blur_sigma_px > 0) cv::GaussianBlur(color, blurred, cv::Size(0, 0), o.blur_sigma_px);
  cv::Mat out(color.rows, color.cols, CV_8UC3);
  const float sigma = static_cast<float>(o.sigma);
  for (int y = 0; y < color.rows; ++y) {
    const cv::Vec3f* src = blurred.ptr<cv::Vec3f>(y);
    cv::Vec3b* dst = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < color.cols; ++x) {
      if (o.enabled && sigma > 0) {
        const std::uint32_t a = rng.bits(), b = rng.bits();
        dst[x] = cv::Vec3b(cv::saturate_cast<uchar>(src[x][0] + sigma * gaussian_[a]),
                           cv::saturate_cast<uchar>(src[x][1] + sigma * gaussian_[a >> 16]),
                           cv::saturate_cast<uchar>(src[x][2] + sigma * gaussian_[b]));
      } else {
        dst[x] = cv::Vec3b(cv::saturate_cast<uchar>(src[x][0]), cv::saturate_cast<uchar>(src[x][1]),
                           cv::saturate_cast<uchar>(src[x][2]));
      }
    }
  }
  return out;
}

}  // namespace amos::synth
