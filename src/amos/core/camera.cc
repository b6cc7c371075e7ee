#include "amos/core/camera.h"

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::core {

void CameraIntrinsics::check() const {
  requirePositive(fx, "fx");
  requirePositive(fy, "fy");
  requirePositive(width, "width");
  requirePositive(height, "height");
  requireOption(std::isfinite(cx) && cx >= 0 && cx <= width, option(cx, "cx"),
                fmt::format("must lie in [0, width = {}], got {}", width, cx), {option(width, "width")});
  requireOption(std::isfinite(cy) && cy >= 0 && cy <= height, option(cy, "cy"),
                fmt::format("must lie in [0, height = {}], got {}", height, cy), {option(height, "height")});
  for (const double* d : {&k1, &k2, &p1, &p2, &k3}) {
    requireOption(std::isfinite(*d), option(*d, "distortion coefficient"), fmt::format("must be finite, got {}", *d));
  }
}

PinholeCamera::PinholeCamera(const CameraIntrinsics& intrinsics) : intr_(intrinsics) {
  intr_.check();
  K_ = (cv::Mat_<double>(3, 3) << intr_.fx, 0, intr_.cx, 0, intr_.fy, intr_.cy, 0, 0, 1);
  dist_ = (cv::Mat_<double>(1, 5) << intr_.k1, intr_.k2, intr_.p1, intr_.p2, intr_.k3);
}

cv::Mat PinholeCamera::K() const { return K_.clone(); }
cv::Mat PinholeCamera::distortion() const { return dist_.clone(); }

Eigen::Matrix3d PinholeCamera::eigenK() const {
  Eigen::Matrix3d K;
  K << intr_.fx, 0, intr_.cx, 0, intr_.fy, intr_.cy, 0, 0, 1;
  return K;
}

std::vector<cv::Point2f> PinholeCamera::undistort(const std::vector<cv::Point2f>& pixels) const {
  if (!intr_.hasDistortion() || pixels.empty()) return pixels;
  std::vector<cv::Point2f> out;
  // P = K keeps the result in pixel units of the same camera.
  cv::undistortPoints(pixels, out, K_, dist_, cv::noArray(), K_);
  return out;
}

std::vector<cv::Point2f> PinholeCamera::distort(const std::vector<cv::Point2f>& undistorted) const {
  if (!intr_.hasDistortion() || undistorted.empty()) return undistorted;
  // Back to normalised rays at z = 1, then projectPoints applies the distortion model and K.
  std::vector<cv::Point3f> rays;
  rays.reserve(undistorted.size());
  for (const auto& p : undistorted)
    rays.emplace_back(static_cast<float>((p.x - cx()) / fx()), static_cast<float>((p.y - cy()) / fy()), 1.0f);
  std::vector<cv::Point2f> raw;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K_, dist_, raw);
  return raw;
}

cv::Rect2d PinholeCamera::undistortedBounds() const {
  const float w = static_cast<float>(intr_.width), h = static_cast<float>(intr_.height);
  if (!intr_.hasDistortion()) return {0, 0, w, h};
  const auto c = undistort({{0, 0}, {w, 0}, {0, h}, {w, h}});
  const double min_u = std::min(c[0].x, c[2].x), max_u = std::max(c[1].x, c[3].x);
  const double min_v = std::min(c[0].y, c[1].y), max_v = std::max(c[2].y, c[3].y);
  return {min_u, min_v, max_u - min_u, max_v - min_v};
}

}  // namespace amos::core
