#include "amos/io/png_encoder.h"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <csetjmp>

#include "amos/core/error.h"

namespace amos::io {
namespace {

void appendToBuffer(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + size);
}

void flushNothing(png_structp) {}

int libpngFilter(PngEncoding::Filter filter) {
  switch (filter) {
    case PngEncoding::Filter::sub:
      return PNG_FILTER_SUB;
    case PngEncoding::Filter::up:
      return PNG_FILTER_UP;
    case PngEncoding::Filter::paeth:
      return PNG_FILTER_PAETH;
    default:
      return PNG_ALL_FILTERS;
  }
}

int colourType(int channels) {
  return channels == 1 ? PNG_COLOR_TYPE_GRAY : channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA;
}

// libpng reports errors by longjmp: this function holds no objects with destructors. False on error.
bool encode(const cv::Mat& image, const PngEncoding& encoding, std::vector<std::uint8_t>& out) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &out, appendToBuffer, flushNothing);
  // Left unset, libpng chooses adaptively among all five filters, as with PNG_ALL_FILTERS.
  if (encoding.filter != PngEncoding::Filter::adaptive)
    png_set_filter(png, PNG_FILTER_TYPE_BASE, libpngFilter(encoding.filter));
  png_set_compression_level(png, std::clamp(encoding.zlib_level, 0, 9));
  png_set_compression_strategy(png, encoding.run_length ? Z_RLE : Z_DEFAULT_STRATEGY);
  const int bit_depth = image.depth() == CV_16U ? 16 : 8;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.cols), static_cast<png_uint_32>(image.rows), bit_depth,
               colourType(image.channels()), PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (image.channels() >= 3) png_set_bgr(png);
  const std::uint16_t probe = 1;
  if (bit_depth == 16 && *reinterpret_cast<const std::uint8_t*>(&probe) == 1)
    png_set_swap(png);  // PNG stores 16-bit samples big-endian
  for (int y = 0; y < image.rows; ++y) png_write_row(png, const_cast<png_bytep>(image.ptr<png_byte>(y)));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

PngEncoding pngEncodingForLevel(int level) { return {PngEncoding::Filter::adaptive, std::clamp(level, 0, 9), false}; }

std::vector<std::uint8_t> encodePng(const cv::Mat& image, const PngEncoding& encoding) {
  const int channels = image.channels();
  core::require(!image.empty() && (image.depth() == CV_8U || image.depth() == CV_16U) &&
                    (channels == 1 || channels == 3 || channels == 4),
                "PNG images must be CV_8U or CV_16U with 1, 3 or 4 channels, not type " +
                    cv::typeToString(image.type()) + (image.empty() ? " (empty)" : ""));
  std::vector<std::uint8_t> bytes;
  bytes.reserve(image.total() * image.elemSize() / 2);
  core::require(encode(image, encoding, bytes), "libpng could not encode the image");
  return bytes;
}

}  // namespace amos::io
