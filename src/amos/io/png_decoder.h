#pragma once
// Any PNG decoded by libpng with the transforms cv::imread's PNG decoder applies, so that the result is
// cv::imread's: palette and 1/2/4-bit images expanded, a tRNS chunk made alpha when four channels are asked for,
// alpha dropped otherwise, RGB swapped to BGR, grey replicated for colour, colour made grey by libpng's
// png_set_rgb_to_gray (0.299 red, 0.587 green), 16-bit samples cut to their high byte unless the output is 16-bit,
// interlaced images de-interlaced, and an eXIf chunk before the image data applied (exif_orientation.h). The output
// type follows the flags (image_read_flags.h). io::readPng uses it for what its fast path does not decode.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace amos::io {

// The image, or an empty Mat with the reason in `problem` (libpng's error, or the unsupported flags or size).
cv::Mat decodePngWithLibpng(const std::uint8_t* data, std::size_t size, int flags, std::string& problem);

}  // namespace amos::io
