#pragma once
// The prepared frames kept for the final fusion, compressed in memory: the final map is fused anew with the final
// trajectory (dense_mapper.h says why), so every kept frame's static depth, left-out dynamic depth and colour must
// outlast the run. Depth is stored in millimetres as 16-bit PNG (lossless at the sensor's 1.5 mm noise floor;
// PNG level 1, fast), colour as JPEG (quality 90). At Dense.scale 0.5 a Bonn frame takes about 100 kB.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "amos/core/pose.h"
#include "amos/dense/frame_preparation.h"

namespace amos::dense {

struct StoredFrame {
  double timestamp = 0;
  core::SE3 T_cw = core::SE3::Identity();  // as tracked (the final fusion takes the final trajectory's)
  std::vector<std::uint8_t> depth_png, removed_png, colour_jpeg;
  std::size_t bytes() const { return depth_png.size() + removed_png.size() + colour_jpeg.size(); }
};

StoredFrame compressFrame(const PreparedFrame& frame, double timestamp, const core::SE3& T_cw);
// Throws core::Error when the bytes do not decode.
PreparedFrame decompressFrame(const StoredFrame& stored);
// The static depth alone (CV_32F metres): what free-space carving reads of each frame a second time.
cv::Mat decompressDepth(const StoredFrame& stored);

}  // namespace amos::dense
