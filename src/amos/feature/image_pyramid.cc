#include "amos/feature/image_pyramid.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

namespace amos::feature {

namespace {
// Smaller levels cannot hold a FAST corner (radius 3) and are not worth building.
constexpr int kMinLevelSize = 8;
}  // namespace

PaddedPyramid::PaddedPyramid(const cv::Mat& gray, const std::vector<float>& scales, int border) : border_(border) {
  cv::Mat previous = gray;
  for (float scale : scales) {
    const cv::Size size(static_cast<int>(std::lround(gray.cols / scale)),
                        static_cast<int>(std::lround(gray.rows / scale)));
    if (size.width < kMinLevelSize || size.height < kMinLevelSize) break;
    cv::Mat current;
    if (size == previous.size()) {
      current = previous;
    } else {
      cv::resize(previous, current, size, 0, 0, cv::INTER_LINEAR);
    }
    cv::Mat padded;
    cv::copyMakeBorder(current, padded, border, border, border, border, cv::BORDER_REFLECT_101);
    padded_.push_back(padded);
    sizes_.push_back(size);
    previous = current;
  }
}

}  // namespace amos::feature
