#include "amos/viewer/frame_image.h"

#include "amos/io/jpeg_codec.h"
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace amos::viewer {

cv::Mat renderFrameOverlay(const cv::Mat& bgr, const cv::Mat& dynamic_mask, const std::vector<cv::Point2f>& keypoints,
                           int max_width) {
  if (bgr.empty()) return cv::Mat();
  cv::Mat out = bgr.clone();
  const bool masked = !dynamic_mask.empty() && dynamic_mask.size() == bgr.size();
  if (masked) {
    cv::Mat red(out.size(), out.type(), cv::Scalar(0, 0, 255)), tinted;
    cv::addWeighted(out, 0.5, red, 0.5, 0, tinted);
    tinted.copyTo(out, dynamic_mask);
  }
  const double scale = bgr.cols > max_width ? static_cast<double>(max_width) / bgr.cols : 1.0;
  if (scale < 1.0) cv::resize(out, out, cv::Size(), scale, scale, cv::INTER_AREA);
  for (const cv::Point2f& k : keypoints) {
    const int x = static_cast<int>(std::lround(k.x)), y = static_cast<int>(std::lround(k.y));
    const bool removed = masked && x >= 0 && y >= 0 && x < dynamic_mask.cols && y < dynamic_mask.rows &&
                         dynamic_mask.at<unsigned char>(y, x) != 0;
    const cv::Point p(static_cast<int>(k.x * scale), static_cast<int>(k.y * scale));
    if (removed) {
      cv::drawMarker(out, p, cv::Scalar(0, 0, 255), cv::MARKER_TILTED_CROSS, 6, 1);
    } else {
      cv::circle(out, p, 2, cv::Scalar(0, 255, 0), cv::FILLED);
    }
  }
  return out;
}

std::vector<unsigned char> encodeJpeg(const cv::Mat& bgr, int quality) {
  if (bgr.empty()) return {};
  return io::encodeJpeg(bgr, quality);
}

}  // namespace amos::viewer
