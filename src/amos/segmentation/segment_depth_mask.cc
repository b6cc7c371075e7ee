#include "amos/segmentation/segment_depth_mask.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "amos/core/error.h"

namespace amos::segmentation {

cv::Mat boxDepthMask(const cv::Mat& depth, const cv::Rect& box, float tolerance) {
  core::require(!box.empty(), "boxDepthMask: empty box");
  cv::Mat full(box.size(), CV_8UC1, cv::Scalar(255));
  if (depth.empty()) return full;
  core::require(depth.type() == CV_32F, "boxDepthMask: depth must be CV_32F metres");
  core::require((box & cv::Rect(0, 0, depth.cols, depth.rows)) == box, "boxDepthMask: box outside the depth image");

  const cv::Mat roi = depth(box);
  const cv::Rect centre(box.width / 4, box.height / 4, std::max(1, box.width / 2), std::max(1, box.height / 2));
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(centre.area()));
  for (int y = centre.y; y < centre.y + centre.height; ++y) {
    const float* row = roi.ptr<float>(y);
    for (int x = centre.x; x < centre.x + centre.width; ++x)
      if (row[x] > 0.f && std::isfinite(row[x])) values.push_back(row[x]);
  }
  // Fewer than a tenth of the centre with depth: the depth cannot be trusted to outline the object.
  if (values.size() * 10 < static_cast<std::size_t>(centre.area())) return full;
  auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  const float object_depth = *mid;

  cv::Mat mask(box.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < box.height; ++y) {
    const float* d = roi.ptr<float>(y);
    uchar* m = mask.ptr<uchar>(y);
    for (int x = 0; x < box.width; ++x)
      if (d[x] > 0.f && std::abs(d[x] - object_depth) <= tolerance) m[x] = 255;
  }
  cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(7, 7)));
  return mask;
}

}  // namespace amos::segmentation
