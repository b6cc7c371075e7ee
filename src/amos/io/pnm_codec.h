#pragma once
// Binary PGM (P5, grey) and PPM (P6, colour) images, as cv::imread / cv::imencode read and write them: the header
// "P5\n<width> <height>\n<maxval>\n" ('#' comments allowed when reading), 8-bit samples for a maxval up to 255,
// 16-bit big-endian ones above; PPM's RGB is BGR in memory. The occupancy grid's format (map_server).
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace amos::io {

// True when the bytes start like a binary PGM or PPM ("P5" or "P6" and a whitespace).
bool looksLikePnm(const std::uint8_t* data, std::size_t size);

// The image, or an empty Mat with the reason in `problem`. Output type per `flags` (image_read_flags.h).
cv::Mat decodePnm(const std::uint8_t* data, std::size_t size, int flags, std::string& problem);

// image: CV_8U or CV_16U, 1 channel (written as P5) or 3 (BGR, written as P6). Throws core::Error for other types.
std::vector<std::uint8_t> encodePnm(const cv::Mat& image);

}  // namespace amos::io
