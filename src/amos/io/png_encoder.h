#pragma once
// PNG encoding with libpng. The default settings are cv::imencode's without parameters (the Sub row filter, zlib
// level 1, run-length matching), so that its files come out byte for byte; a fixed filter chosen by the caller is
// faster than libpng's adaptive choice, which tries all five filters on every row (synth::writePng).
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace amos::io {

struct PngEncoding {
  enum class Filter { sub, up, paeth, adaptive };  // adaptive: libpng's choice per row
  Filter filter = Filter::sub;
  int zlib_level = 1;      // 0 (stored) to 9
  bool run_length = true;  // zlib's Z_RLE strategy; else Z_DEFAULT_STRATEGY
};

// The encoding cv::imencode uses with cv::IMWRITE_PNG_COMPRESSION = level: libpng's adaptive filters, zlib's
// default strategy, the level clamped to 0..9.
PngEncoding pngEncodingForLevel(int level);

// image: CV_8U or CV_16U with 1 (grey), 3 (BGR) or 4 (BGRA) channels. Throws core::Error for other types.
std::vector<std::uint8_t> encodePng(const cv::Mat& image, const PngEncoding& encoding = {});

}  // namespace amos::io
