#pragma once
// The EXIF orientation cv::imread applies to JPEG and PNG images (unless cv::IMREAD_IGNORE_ORIENTATION or
// cv::IMREAD_UNCHANGED): tag 0x0112 of the first image file directory of a TIFF-structured EXIF block.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>

namespace amos::io {

// The orientation (1 to 8) of the EXIF block of `size` bytes at `tiff` (starting with "II*\0" or "MM\0*"); 1 (as
// stored) when there is none or the block is malformed.
int exifOrientation(const std::uint8_t* tiff, std::size_t size);

// Turns `image` upright for `orientation` (1 to 8; other values leave it as it is), as cv::imread does.
void applyExifOrientation(int orientation, cv::Mat& image);

}  // namespace amos::io
