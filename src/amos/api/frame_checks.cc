#include "amos/api/frame_checks.h"

#include <fmt/format.h>

#include <cmath>
#include <initializer_list>

#include "amos/core/error.h"

namespace amos::api {

namespace {

void checkImage(const cv::Mat& image, const char* name, std::initializer_list<int> types, const char* expected,
                cv::Size size, const std::string& method) {
  core::require(!image.empty(), fmt::format("{}: argument '{}' is empty (expected {} of {}x{})", method, name,
                                            expected, size.width, size.height));
  bool type_ok = false;
  for (const int t : types) type_ok = type_ok || image.type() == t;
  core::require(type_ok, fmt::format("{}: argument '{}' must be {}, got {}", method, name, expected,
                                     typeName(image.type())));
  core::require(image.dims == 2 && image.size() == size,
                fmt::format("{}: argument '{}' is {}x{}, the settings say {}x{} (Camera.width x Camera.height)",
                            method, name, image.cols, image.rows, size.width, size.height));
}

}  // namespace

std::string typeName(int type) {
  static const char* const kDepths[] = {"8U", "8S", "16U", "16S", "32S", "32F", "64F", "16F"};
  return fmt::format("CV_{}C{}", kDepths[CV_MAT_DEPTH(type)], CV_MAT_CN(type));
}

void checkFrame(const FrameArguments& frame, cv::Size size, std::optional<double> last_timestamp,
                const std::string& method) {
  checkImage(frame.bgr, "bgr", {CV_8UC3}, "CV_8UC3 (8-bit BGR)", size, method);
  checkImage(frame.depth, "depth", {CV_16UC1, CV_32FC1}, "CV_16UC1 (raw) or CV_32FC1 (metres)", size, method);
  if (!frame.prior_mask.empty())
    checkImage(frame.prior_mask, "prior_mask", {CV_8UC1}, "CV_8UC1 (non-zero = dynamic)", size, method);
  core::require(std::isfinite(frame.timestamp),
                fmt::format("{}: argument 'timestamp' must be finite, got {}", method, frame.timestamp));
  if (last_timestamp) {
    core::require(frame.timestamp > *last_timestamp,
                  fmt::format("{}: argument 'timestamp' must increase: {:.6f} after {:.6f}", method, frame.timestamp,
                              *last_timestamp));
  }
}

}  // namespace amos::api
