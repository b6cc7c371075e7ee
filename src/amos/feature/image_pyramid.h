#pragma once
// Scale pyramid whose levels carry a reflected border, so that patches around keypoints near the image edge
// (orientation, descriptor) can be read without bounds checks.
#include <opencv2/core.hpp>

#include <vector>

namespace amos::feature {

class PaddedPyramid {
 public:
  // Level l has size round(gray.size / scales[l]) and is resized from level l-1 (bilinear, as ORB-SLAM2 does).
  // Levels smaller than 8x8 pixels are not built (numLevels() may be less than scales.size()).
  PaddedPyramid(const cv::Mat& gray, const std::vector<float>& scales, int border);

  int numLevels() const { return static_cast<int>(padded_.size()); }
  int border() const { return border_; }
  cv::Size size(int level) const { return sizes_[level]; }
  // The level image without its border (a view into the padded buffer).
  cv::Mat level(int level) const {
    return padded_[level](cv::Rect(border_, border_, sizes_[level].width, sizes_[level].height));
  }
  // The whole buffer: level pixel (x, y) is at (x + border, y + border).
  const cv::Mat& padded(int level) const { return padded_[level]; }

 private:
  int border_;
  std::vector<cv::Mat> padded_;
  std::vector<cv::Size> sizes_;
};

}  // namespace amos::feature
