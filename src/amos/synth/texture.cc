#include "amos/synth/texture.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::synth {

Texture::Texture(const cv::Mat& bgr, const cv::Mat& alpha, bool repeat, bool mipmaps) : repeat_(repeat) {
  core::require(!bgr.empty() && bgr.type() == CV_8UC3, "Texture: colour image must be a non-empty CV_8UC3");
  core::require(alpha.empty() || (alpha.type() == CV_8UC1 && alpha.size() == bgr.size()),
                "Texture: alpha must be CV_8UC1 of the colour image's size");
  levels_.push_back(bgr.clone());
  while (mipmaps && levels_.back().cols > 4 && levels_.back().rows > 4) {
    const cv::Mat& prev = levels_.back();
    cv::Mat next;
    cv::resize(prev, next, cv::Size((prev.cols + 1) / 2, (prev.rows + 1) / 2), 0, 0, cv::INTER_AREA);
    levels_.push_back(next);
  }
  if (!alpha.empty()) alpha_ = alpha.clone();
}

namespace {
// Integer texel indices and weight along one axis, wrapping or clamping.
inline void axis(double coord, int size, bool repeat, int& i0, int& i1, float& frac) {
  const double x = coord * size - 0.5;
  const double fl = std::floor(x);
  frac = static_cast<float>(x - fl);
  long long i = static_cast<long long>(fl);
  if (repeat) {
    long long m = i % size;
    if (m < 0) m += size;
    i0 = static_cast<int>(m);
    i1 = i0 + 1 == size ? 0 : i0 + 1;
  } else {
    i0 = static_cast<int>(std::clamp<long long>(i, 0, size - 1));
    i1 = static_cast<int>(std::clamp<long long>(i + 1, 0, size - 1));
  }
}
}  // namespace

cv::Vec3f Texture::sampleLevel(int level, double s, double t) const {
  const cv::Mat& img = levels_[static_cast<std::size_t>(level)];
  int x0, x1, y0, y1;
  float fx, fy;
  axis(s, img.cols, repeat_, x0, x1, fx);
  axis(t, img.rows, repeat_, y0, y1, fy);
  const uchar* r0 = img.ptr<uchar>(y0);
  const uchar* r1 = img.ptr<uchar>(y1);
  const uchar* a = r0 + 3 * x0;
  const uchar* b = r0 + 3 * x1;
  const uchar* c = r1 + 3 * x0;
  const uchar* d = r1 + 3 * x1;
  const float w00 = (1 - fx) * (1 - fy), w01 = fx * (1 - fy), w10 = (1 - fx) * fy, w11 = fx * fy;
  return {w00 * a[0] + w01 * b[0] + w10 * c[0] + w11 * d[0], w00 * a[1] + w01 * b[1] + w10 * c[1] + w11 * d[1],
          w00 * a[2] + w01 * b[2] + w10 * c[2] + w11 * d[2]};
}

cv::Vec3f Texture::sample(double s, double t, double lod) const {
  const int last = levelCount() - 1;
  if (!(lod > 0)) return sampleLevel(0, s, t);
  if (lod >= last) return sampleLevel(last, s, t);
  // "Brilinear": blend two levels only in the middle half between them, one level elsewhere. Halves the cost of
  // trilinear filtering and still has no visible step between levels.
  const int l0 = static_cast<int>(lod);
  const float f = std::clamp(static_cast<float>(lod - l0) * 2.0f - 0.5f, 0.0f, 1.0f);
  if (f <= 0.0f) return sampleLevel(l0, s, t);
  if (f >= 1.0f) return sampleLevel(l0 + 1, s, t);
  return sampleLevel(l0, s, t) * (1 - f) + sampleLevel(l0 + 1, s, t) * f;
}

float Texture::alpha(double s, double t) const {
  if (alpha_.empty()) return 1.0f;
  int x0, x1, y0, y1;
  float fx, fy;
  axis(s, alpha_.cols, repeat_, x0, x1, fx);
  axis(t, alpha_.rows, repeat_, y0, y1, fy);
  const uchar* r0 = alpha_.ptr<uchar>(y0);
  const uchar* r1 = alpha_.ptr<uchar>(y1);
  const float v = (1 - fx) * (1 - fy) * r0[x0] + fx * (1 - fy) * r0[x1] + (1 - fx) * fy * r1[x0] + fx * fy * r1[x1];
  return v * (1.0f / 255.0f);
}

}  // namespace amos::synth
