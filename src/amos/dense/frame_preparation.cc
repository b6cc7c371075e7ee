#include "amos/dense/frame_preparation.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "amos/core/error.h"

namespace amos::dense {

namespace {

cv::Mat disk(int radius) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
}

cv::Mat undistorted(const cv::Mat& image, const cv::Mat& map_x, const cv::Mat& map_y, int interpolation) {
  if (map_x.empty() || image.empty()) return image;
  cv::Mat out;
  cv::remap(image, out, map_x, map_y, interpolation, cv::BORDER_CONSTANT, cv::Scalar::all(0));
  return out;
}

// Nearest neighbour: a depth reading is never averaged with its neighbours (across an edge that makes a point in
// mid-air).
cv::Mat resized(const cv::Mat& image, cv::Size size, int interpolation) {
  if (image.size() == size) return image;
  cv::Mat out;
  cv::resize(image, out, size, 0, 0, interpolation);
  return out;
}

}  // namespace

core::CameraIntrinsics scaledIntrinsics(const core::CameraIntrinsics& camera, double scale) {
  core::CameraIntrinsics out;
  out.width = static_cast<int>(std::lround(camera.width * scale));
  out.height = static_cast<int>(std::lround(camera.height * scale));
  const double sx = static_cast<double>(out.width) / camera.width, sy = static_cast<double>(out.height) / camera.height;
  out.fx = camera.fx * sx;
  out.fy = camera.fy * sy;
  out.cx = (camera.cx + 0.5) * sx - 0.5;
  out.cy = (camera.cy + 0.5) * sy - 0.5;
  return out;
}

cv::Mat depthEdges(const cv::Mat& depth, double edge_jump, int edge_margin_px) {
  cv::Mat high, low;
  const cv::Mat square = cv::Mat::ones(3, 3, CV_8U);
  cv::dilate(depth, high, square);
  cv::erode(depth, low, square);  // 0 next to a missing reading: its border counts as an edge
  cv::Mat edges = (high - low) > edge_jump * depth;
  edges &= depth > 0;
  if (edge_margin_px > 0) cv::dilate(edges, edges, disk(edge_margin_px));
  return edges;
}

FramePreparer::FramePreparer(const core::CameraIntrinsics& camera, const DenseOptions& options)
    : camera_(camera), scaled_(scaledIntrinsics(camera, options.scale)), options_(options) {
  if (camera.hasDistortion()) {
    const core::PinholeCamera pinhole(camera);
    cv::initUndistortRectifyMap(pinhole.K(), pinhole.distortion(), cv::Mat(), pinhole.K(),
                                cv::Size(camera.width, camera.height), CV_32FC1, map_x_, map_y_);
  }
}

PreparedFrame FramePreparer::prepare(const FrameImages& frame) const {
  const cv::Size size(camera_.width, camera_.height);
  core::require(frame.depth.type() == CV_32F && frame.depth.size() == size,
                fmt::format("dense fusion: depth must be CV_32F {}x{}", size.width, size.height));
  core::require(frame.bgr.type() == CV_8UC3 && frame.bgr.size() == size,
                fmt::format("dense fusion: colour must be CV_8UC3 {}x{}", size.width, size.height));
  core::require(frame.dynamic_mask.empty() || (frame.dynamic_mask.type() == CV_8U && frame.dynamic_mask.size() == size),
                "dense fusion: the dynamic mask must be CV_8U of the image's size");
  const cv::Mat depth = undistorted(frame.depth, map_x_, map_y_, cv::INTER_NEAREST);
  const cv::Mat bgr = undistorted(frame.bgr, map_x_, map_y_, cv::INTER_LINEAR);
  const cv::Mat in_range = (depth >= options_.min_depth) & (depth <= options_.max_depth);
  cv::Mat dynamic = cv::Mat::zeros(size, CV_8U);
  if (!frame.dynamic_mask.empty()) {
    dynamic = undistorted(frame.dynamic_mask, map_x_, map_y_, cv::INTER_NEAREST) > 0;
    if (options_.mask_margin_px > 0) cv::dilate(dynamic, dynamic, disk(options_.mask_margin_px));
  }
  const cv::Mat keep = in_range & ~dynamic & ~depthEdges(depth, options_.edge_jump, options_.edge_margin_px);
  cv::Mat kept = cv::Mat::zeros(size, CV_32F), removed = cv::Mat::zeros(size, CV_32F);
  depth.copyTo(kept, keep);
  depth.copyTo(removed, in_range & dynamic);
  const cv::Size out(scaled_.width, scaled_.height);
  return {resized(kept, out, cv::INTER_NEAREST), resized(removed, out, cv::INTER_NEAREST),
          resized(bgr, out, cv::INTER_AREA)};
}

}  // namespace amos::dense
