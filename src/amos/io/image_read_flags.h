#pragma once
// The flags of the image readers (io::readImage, io::decodeImage, io::readPng): the values of OpenCV's
// cv::ImreadModes, so that a caller's flags mean what they meant to cv::imread, and the output type they give.
#include <cstdint>
#include <optional>
#include <string>

namespace amos::io {

inline constexpr int kReadUnchanged = -1;          // cv::IMREAD_UNCHANGED: the file's channels and depth
inline constexpr int kReadGrayscale = 0;           // cv::IMREAD_GRAYSCALE: 1 channel, 8 bits
inline constexpr int kReadColor = 1;               // cv::IMREAD_COLOR: 3 channels BGR, 8 bits
inline constexpr int kReadAnyDepth = 2;            // cv::IMREAD_ANYDEPTH: keep 16 bits
inline constexpr int kReadAnyColor = 4;            // cv::IMREAD_ANYCOLOR: keep colour, else grey
inline constexpr int kReadIgnoreOrientation = 128;  // cv::IMREAD_IGNORE_ORIENTATION: no EXIF rotation

// The type cv::imread gives with `flags` for an image whose own type (every channel, full depth) is `file_type`;
// nullopt for flags these readers do not support (cv::IMREAD_REDUCED_*, cv::IMREAD_LOAD_GDAL, negative values
// other than kReadUnchanged).
std::optional<int> readType(int flags, int file_type);

// True when cv::imread would rotate the image by its EXIF orientation with these flags.
bool appliesOrientation(int flags);

// Why an image of this size is not decoded (beyond OpenCV's limits CV_IO_MAX_IMAGE_WIDTH / _HEIGHT of 2^20 pixels a
// side and CV_IO_MAX_IMAGE_PIXELS of 2^30 pixels, for which cv::imread throws), or nullopt.
std::optional<std::string> sizeProblem(std::uint64_t width, std::uint64_t height);

}  // namespace amos::io
