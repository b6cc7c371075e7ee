#pragma once
// The prepared frames kept for the final fusion, compressed in memory: the final map is fused anew with the final
// trajectory (dense_mapper.h says why), so every kept frame's static depth, left-out dynamic depth and colour must
// outlast the run. Depth is stored in millimetres, 16 bits (lossless at the sensor's 1.5 mm noise floor), as a zlib
// stream at level 1 (io/zlib_stream.h): a 320x240 Bonn depth image in 0.6 ms and 28 kB, where a PNG took 4.7 ms and
// 38 kB (libpng's row filters cost more than they save on depth); colour as JPEG (quality 90). At Dense.scale 0.5 a
// Bonn frame takes about 60 kB. Compressing runs in the fusion thread beside tracking, for every frame: its cost is
// what `--dense` takes from the run's frame rate.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "amos/core/pose.h"
#include "amos/dense/frame_preparation.h"

namespace amos::dense {

struct StoredFrame {
  double timestamp = 0;
  core::SE3 T_cw = core::SE3::Identity();  // as tracked (the final fusion takes the final trajectory's)
  int rows = 0, cols = 0;  // of the depth images
  std::vector<std::uint8_t> depth_mm_zlib, removed_mm_zlib, colour_jpeg;
  std::size_t bytes() const { return depth_mm_zlib.size() + removed_mm_zlib.size() + colour_jpeg.size(); }
};

StoredFrame compressFrame(const PreparedFrame& frame, double timestamp, const core::SE3& T_cw);
// Throws core::Error when the bytes do not decode.
PreparedFrame decompressFrame(const StoredFrame& stored);
// The static depth alone (CV_32F metres): what free-space carving reads of each frame a second time.
cv::Mat decompressDepth(const StoredFrame& stored);

}  // namespace amos::dense
