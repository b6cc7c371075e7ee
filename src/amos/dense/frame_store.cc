#include "amos/dense/frame_store.h"

#include "amos/core/error.h"
#include "amos/io/image_codecs.h"

namespace amos::dense {

namespace {

std::vector<std::uint8_t> depthPng(const cv::Mat& metres) {
  cv::Mat millimetres;
  metres.convertTo(millimetres, CV_16U, 1000.0);  // rounds; depths beyond 65.5 m saturate (never fused anyway)
  return io::encodeImage(".png", millimetres, io::pngCompression(1));
}

cv::Mat depthFromPng(const std::vector<std::uint8_t>& bytes) {
  const cv::Mat millimetres = io::decodeImage(bytes, io::kReadUnchanged);
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
  out.colour_jpeg = io::encodeImage(".jpg", frame.bgr, io::jpegQuality(90));
  return out;
}

PreparedFrame decompressFrame(const StoredFrame& stored) {
  PreparedFrame out;
  out.depth = depthFromPng(stored.depth_png);
  out.removed = depthFromPng(stored.removed_png);
  out.bgr = io::decodeImage(stored.colour_jpeg, io::kReadColor);
  core::require(out.bgr.type() == CV_8UC3 && out.bgr.size() == out.depth.size(),
                "dense fusion: a kept frame's colour does not decode");
  return out;
}

cv::Mat decompressDepth(const StoredFrame& stored) { return depthFromPng(stored.depth_png); }

}  // namespace amos::dense
