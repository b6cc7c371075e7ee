#include "amos/dense/frame_store.h"

#include "amos/core/error.h"
#include "amos/io/image_codecs.h"
#include "amos/io/zlib_stream.h"

namespace amos::dense {

namespace {

std::vector<std::uint8_t> compressedMillimetres(const cv::Mat& metres) {
  cv::Mat millimetres;
  metres.convertTo(millimetres, CV_16U, 1000.0);  // rounds; depths beyond 65.5 m saturate (never fused anyway)
  return io::deflateBytes(millimetres.data, millimetres.total() * millimetres.elemSize(), 1);
}

cv::Mat metresFrom(const std::vector<std::uint8_t>& stream, int rows, int cols) {
  cv::Mat millimetres(rows, cols, CV_16U);
  try {
    io::inflateBytes(stream, millimetres.data, millimetres.total() * millimetres.elemSize());
  } catch (const core::Error& e) {
    throw core::Error(std::string("dense fusion: a kept frame's depth does not decode: ") + e.what());
  }
  cv::Mat metres;
  millimetres.convertTo(metres, CV_32F, 1e-3);
  return metres;
}

}  // namespace

StoredFrame compressFrame(const PreparedFrame& frame, double timestamp, const core::SE3& T_cw) {
  StoredFrame out;
  out.timestamp = timestamp;
  out.T_cw = T_cw;
  core::require(frame.depth.type() == CV_32F && frame.removed.type() == CV_32F &&
                    frame.removed.size() == frame.depth.size(),
                "dense fusion: a prepared frame's depth images must be CV_32F of one size");
  out.rows = frame.depth.rows;
  out.cols = frame.depth.cols;
  out.depth_mm_zlib = compressedMillimetres(frame.depth);
  out.removed_mm_zlib = compressedMillimetres(frame.removed);
  out.colour_jpeg = io::encodeImage(".jpg", frame.bgr, io::jpegQuality(90));
  return out;
}

PreparedFrame decompressFrame(const StoredFrame& stored) {
  PreparedFrame out;
  out.depth = metresFrom(stored.depth_mm_zlib, stored.rows, stored.cols);
  out.removed = metresFrom(stored.removed_mm_zlib, stored.rows, stored.cols);
  out.bgr = io::decodeImage(stored.colour_jpeg, io::kReadColor);
  core::require(out.bgr.type() == CV_8UC3 && out.bgr.size() == out.depth.size(),
                "dense fusion: a kept frame's colour does not decode");
  return out;
}

cv::Mat decompressDepth(const StoredFrame& stored) { return metresFrom(stored.depth_mm_zlib, stored.rows, stored.cols); }

}  // namespace amos::dense
