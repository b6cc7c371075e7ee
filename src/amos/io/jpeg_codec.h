#pragma once
// JPEG with libjpeg(-turbo), set up as cv::imdecode / cv::imencode set it up (libjpeg's defaults: islow DCT, fancy
// upsampling, 4:2:0 chroma, Huffman tables not optimised, baseline quantisation tables), so that with the same
// library the pixels and bytes are OpenCV's. Decoding applies the EXIF orientation of an APP1 marker as cv::imread
// does (exif_orientation.h). CMYK JPEGs are not supported.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace amos::io {

// The image, or an empty Mat with the reason in `problem`. Output type per `flags` (image_read_flags.h): 8 bits,
// 1 channel or 3 (BGR).
cv::Mat decodeJpeg(const std::uint8_t* data, std::size_t size, int flags, std::string& problem);

// image: CV_8UC1 (grey), CV_8UC3 (BGR) or CV_8UC4 (BGRA, alpha dropped); quality 0..100 (clamped; OpenCV's default
// is 95). Throws core::Error for other types.
std::vector<std::uint8_t> encodeJpeg(const cv::Mat& image, int quality = 95);

}  // namespace amos::io
