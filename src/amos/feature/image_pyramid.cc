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
    // The level is written straight into the middle of its padded buffer, then the border is filled around it
    // in place (BORDER_ISOLATED: the border reflects the level itself, not the surrounding buffer).
    cv::Mat padded(size.height + 2 * border, size.width + 2 * border, CV_8UC1);
    cv::Mat inner = padded(cv::Rect(border, border, size.width, size.height));
    if (size == previous.size()) {
      previous.copyTo(inner);
    } else {
      cv::resize(previous, inner, size, 0, 0, cv::INTER_LINEAR);
    }
    cv::copyMakeBorder(inner, padded, border, border, border, border, cv::BORDER_REFLECT_101 | cv::BORDER_ISOLATED);
    padded_.push_back(padded);
    sizes_.push_back(size);
    previous = inner;
  }
}

}  // namespace amos::feature
