#pragma once
// The frame picture of the viewer: the colour image with the dynamic mask tinted red, the keypoints the mask kept
// as green dots and those it removed as red crosses; JPEG-encoded for /api/frame.jpg. Runs in the publisher
// thread, a few times a second.
#include <opencv2/core.hpp>

#include <vector>

namespace amos::viewer {

// `dynamic_mask` may be empty (mode none: every keypoint kept). A keypoint is removed when the mask is set at its
// pixel (how system::SlamSystem drops it). Scaled to at most `max_width` pixels wide.
cv::Mat renderFrameOverlay(const cv::Mat& bgr, const cv::Mat& dynamic_mask, const std::vector<cv::Point2f>& keypoints,
                           int max_width = 640);

std::vector<unsigned char> encodeJpeg(const cv::Mat& bgr, int quality = 75);

}  // namespace amos::viewer
