#include "amos/feature/orientation.h"

#include <cmath>
#include <cstdint>

namespace amos::feature {

IntensityCentroid::IntensityCentroid(int radius) : radius_(radius), half_width_(static_cast<size_t>(radius + 1)) {
  for (int v = 0; v <= radius; ++v)
    half_width_[static_cast<size_t>(v)] = static_cast<int>(std::floor(std::sqrt(radius * radius - v * v) + 0.5));
}

float IntensityCentroid::angleDeg(const cv::Mat& image, int x, int y) const {
  const std::uint8_t* center = image.ptr<std::uint8_t>(y) + x;
  const int step = static_cast<int>(image.step1());
  // m10 = sum u I(u, v), m01 = sum v I(u, v); rows +v and -v are visited together.
  long m10 = 0, m01 = 0;
  for (int u = -radius_; u <= radius_; ++u) m10 += u * center[u];
  for (int v = 1; v <= radius_; ++v) {
    const int w = half_width_[static_cast<size_t>(v)];
    const std::uint8_t* below = center + v * step;
    const std::uint8_t* above = center - v * step;
    long difference = 0;
    for (int u = -w; u <= w; ++u) {
      const int b = below[u], a = above[u];
      m10 += u * (b + a);
      difference += b - a;
    }
    m01 += v * difference;
  }
  float angle = static_cast<float>(std::atan2(static_cast<double>(m01), static_cast<double>(m10)) * 180.0 / M_PI);
  if (angle < 0) angle += 360.0f;
  if (angle >= 360.0f) angle -= 360.0f;
  return angle;
}

}  // namespace amos::feature
