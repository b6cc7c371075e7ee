#include "amos/camera/openni2_convert.h"

#include <fmt/format.h>

#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::camera {

namespace {

void checkBuffer(const void* data, int width, int height, int stride_bytes, int bytes_per_pixel, const char* what) {
  core::require(data != nullptr && width > 0 && height > 0,
                fmt::format("{} buffer: no data or an empty {}x{} image", what, width, height));
  core::require(stride_bytes >= width * bytes_per_pixel,
                fmt::format("{} buffer: row stride {} bytes is shorter than {} pixels of {} bytes", what, stride_bytes,
                            width, bytes_per_pixel));
}

}  // namespace

cv::Mat rgb888ToBgr(const void* data, int width, int height, int stride_bytes) {
  checkBuffer(data, width, height, stride_bytes, 3, "RGB888");
  const cv::Mat rgb(height, width, CV_8UC3, const_cast<void*>(data), static_cast<std::size_t>(stride_bytes));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

cv::Mat depthToMetres(const void* data, int width, int height, int stride_bytes, double metres_per_unit) {
  checkBuffer(data, width, height, stride_bytes, 2, "depth");
  core::require(metres_per_unit > 0, fmt::format("depth buffer: unit must be positive, got {}", metres_per_unit));
  const cv::Mat raw(height, width, CV_16U, const_cast<void*>(data), static_cast<std::size_t>(stride_bytes));
  cv::Mat metres;
  raw.convertTo(metres, CV_32F, metres_per_unit);
  return metres;
}

double deviceSeconds(std::uint64_t microseconds) { return static_cast<double>(microseconds) / 1e6; }

}  // namespace amos::camera
