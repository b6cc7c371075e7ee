#include "amos/dense/frame_store.h"

#include <opencv2/imgcodecs.hpp>

#include "amos/core/error.h"

namespace amos::dense {

namespace {

std::vector<std::uint8_t> depthPng(const cv::Mat& metres) {
  cv::Mat millimetres;
  metres.convertTo(millimetres, CV_16U, 1000.0);  // rounds; depths beyond 65.5 m saturate (never fused anyway)
  std::vector<std::uint8_t> bytes;
  cv::imencode(".png", millimetres, bytes, {cv::IMWRITE_PNG_COMPRESSION, 1});
  return bytes;
}

cv::Mat depthFromPng(const std::vector<std::uint8_t>& bytes) {
  const cv::Mat millimetres = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  core::require(millimetres.type() == CV_16U, "dense fusion: a kept frame's depth does not decode");
  cv::Mat metres;
  millimetres.convertTo(metres, CV_32F, 1e-3);
  return metres;
}

}  // namespace

StoredFrame compressFrame(const PreparedFrame& frame, double timestamp, const core::SE3& T_cw) {
  StoredFrame out;
  out.timestamp = timestamp;
  out.T_cw = T_cw;
  out.depth_png = depthPng(frame.depth);
  out.removed_png = depthPng(frame.removed);
  cv::imencode(".jpg", frame.bgr, out.colour_jpeg, {cv::IMWRITE_JPEG_QUALITY, 90});
  return out;
}

PreparedFrame decompressFrame(const StoredFrame& stored) {
  PreparedFrame out;
  out.depth = depthFromPng(stored.depth_png);
  out.removed = depthFromPng(stored.removed_png);
  out.bgr = cv::imdecode(stored.colour_jpeg, cv::IMREAD_COLOR);
  core::require(out.bgr.type() == CV_8UC3 && out.bgr.size() == out.depth.size(),
                "dense fusion: a kept frame's colour does not decode");
  return out;
}

cv::Mat decompressDepth(const StoredFrame& stored) { return depthFromPng(stored.depth_png); }

}  // namespace amos::dense
