#pragma once
// The checks of amos::Slam's frame arguments (include/amos/slam.h, track()), each failure a core::Error whose
// message names the method and the argument at fault, so that a caller's mistake is told apart from the library's.
#include <opencv2/core.hpp>

#include <optional>
#include <string>

namespace amos::api {

struct FrameArguments {
  const cv::Mat& bgr;
  const cv::Mat& depth;
  double timestamp;
  const cv::Mat& prior_mask;
};

// bgr CV_8UC3, depth CV_16UC1 or CV_32FC1, prior_mask empty or CV_8UC1, all of `size`; the time stamp finite and
// greater than `last_timestamp` (when there was a frame before). `method` names the call ("amos::Slam::track").
void checkFrame(const FrameArguments& frame, cv::Size size, std::optional<double> last_timestamp,
                const std::string& method);

// OpenCV's name of a type ("CV_8UC3").
std::string typeName(int type);

}  // namespace amos::api
