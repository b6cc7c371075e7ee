#pragma once
// Pure conversions from the raw buffers an OpenNI2 stream hands out to the images the SLAM loop reads
// (io::RgbdFrame): no OpenNI2 types, so they are tested without a device. `stride_bytes` is the length of one row
// in the buffer (at least width * bytes per pixel); the output is a new, continuous image.
#include <opencv2/core.hpp>

#include <cstdint>

namespace amos::camera {

// PIXEL_FORMAT_RGB888 (R, G, B bytes) -> CV_8UC3 in OpenCV's B, G, R order.
cv::Mat rgb888ToBgr(const void* data, int width, int height, int stride_bytes);

// 16-bit depth in units of `metres_per_unit` (PIXEL_FORMAT_DEPTH_1_MM: 0.001) -> CV_32F metres; 0 (no depth)
// stays 0.
cv::Mat depthToMetres(const void* data, int width, int height, int stride_bytes, double metres_per_unit = 0.001);

// A device time stamp in microseconds as seconds (divided, so that whole microseconds print back exactly).
double deviceSeconds(std::uint64_t microseconds);

}  // namespace amos::camera
