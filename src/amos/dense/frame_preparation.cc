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
    // The distortion acts on normalised coordinates: the scaled image has the same coefficients.
    core::CameraIntrinsics distorted = scaled_;
    distorted.k1 = camera.k1;
    distorted.k2 = camera.k2;
    distorted.p1 = camera.p1;
    distorted.p2 = camera.p2;
    distorted.k3 = camera.k3;
    const core::PinholeCamera pinhole(distorted);
    cv::initUndistortRectifyMap(pinhole.K(), pinhole.distortion(), cv::Mat(), pinhole.K(),
                                cv::Size(scaled_.width, scaled_.height), CV_32FC1, map_x_, map_y_);
  }
}

// Everything at Dense.scale, the images scaled first: the work (undistortion, morphology, compression) shrinks with
// the pixel count (at 0.5 a Bonn frame takes ~4 ms instead of ~11 ms), and the margins are scaled with them.
PreparedFrame FramePreparer::prepare(const FrameImages& frame) const {
  const cv::Size size(camera_.width, camera_.height);
  core::require(frame.depth.type() == CV_32F && frame.depth.size() == size,
                fmt::format("dense fusion: depth must be CV_32F {}x{}", size.width, size.height));
  core::require(frame.bgr.type() == CV_8UC3 && frame.bgr.size() == size,
                fmt::format("dense fusion: colour must be CV_8UC3 {}x{}", size.width, size.height));
  core::require(frame.dynamic_mask.empty() || (frame.dynamic_mask.type() == CV_8U && frame.dynamic_mask.size() == size),
                "dense fusion: the dynamic mask must be CV_8U of the image's size");
  const cv::Size out(scaled_.width, scaled_.height);
  const auto scaledMargin = [&](int pixels) {
    return pixels == 0 ? 0 : std::max(1, static_cast<int>(std::lround(pixels * options_.scale)));
  };
  const cv::Mat depth = undistorted(resized(frame.depth, out, cv::INTER_NEAREST), map_x_, map_y_, cv::INTER_NEAREST);
  const cv::Mat bgr = undistorted(resized(frame.bgr, out, cv::INTER_AREA), map_x_, map_y_, cv::INTER_LINEAR);
  const cv::Mat in_range = (depth >= options_.min_depth) & (depth <= options_.max_depth);
  cv::Mat dynamic = cv::Mat::zeros(out, CV_8U);
  if (!frame.dynamic_mask.empty()) {
    // Any dynamic pixel under a scaled pixel makes it dynamic (max, not nearest: a thin mover is not lost).
    // Into a Mat of its own: the caller's mask is shared with the run, which reads it after this (dilating into a
    // header of it wrote the run's mask from this thread).
    cv::Mat mask = frame.dynamic_mask;
    if (mask.size() != out) {
      cv::Mat grown;
      cv::dilate(frame.dynamic_mask, grown, cv::Mat::ones(3, 3, CV_8U));
      mask = resized(grown, out, cv::INTER_NEAREST);
    }
    dynamic = undistorted(mask, map_x_, map_y_, cv::INTER_NEAREST) > 0;
    const int margin = scaledMargin(options_.mask_margin_px);
    if (margin > 0) cv::dilate(dynamic, dynamic, disk(margin));
  }
  const cv::Mat keep =
      in_range & ~dynamic & ~depthEdges(depth, options_.edge_jump, scaledMargin(options_.edge_margin_px));
  cv::Mat kept = cv::Mat::zeros(out, CV_32F), removed = cv::Mat::zeros(out, CV_32F);
  depth.copyTo(kept, keep);
  depth.copyTo(removed, in_range & dynamic);
  return {kept, removed, bgr};
}

}  // namespace amos::dense
