#include "amos/synth/png_writer.h"

#include <png.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "amos/core/error.h"

namespace amos::synth {

namespace {

void appendToBuffer(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + size);
}

void flushNothing(png_structp) {}

bool littleEndianHost() {
  const std::uint16_t probe = 1;
  return *reinterpret_cast<const unsigned char*>(&probe) == 1;
}

// libpng reports errors by longjmp: keep this function free of objects with destructors. Returns false on error.
bool encode(const cv::Mat& image, int filter, std::vector<unsigned char>& out) {
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
  const int bit_depth = image.depth() == CV_16U ? 16 : 8;
  const int colour = image.channels() == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.cols), static_cast<png_uint_32>(image.rows), bit_depth, colour,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, filter);
  png_set_compression_level(png, 1);
  png_set_compression_strategy(png, Z_RLE);
  png_write_info(png, info);
  if (colour == PNG_COLOR_TYPE_RGB) png_set_bgr(png);
  if (bit_depth == 16 && littleEndianHost()) png_set_swap(png);  // PNG stores 16-bit samples big-endian
  for (int y = 0; y < image.rows; ++y) png_write_row(png, const_cast<png_bytep>(image.ptr<png_byte>(y)));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void writePng(const std::string& path, const cv::Mat& image) {
  core::require(!image.empty() && (image.type() == CV_8UC3 || image.type() == CV_8UC1 || image.type() == CV_16UC1),
                "synth: PNG images must be CV_8UC3, CV_8UC1 or CV_16UC1 (" + path + ")");
  std::vector<unsigned char> bytes;
  bytes.reserve(image.total() * image.elemSize() / 2);
  const int filter = image.channels() == 3 ? PNG_FILTER_PAETH : PNG_FILTER_UP;
  core::require(encode(image, filter, bytes), "synth: cannot encode " + path);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  core::require(f != nullptr, "synth: cannot write " + path);
  const std::size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
  const bool closed = std::fclose(f) == 0;
  core::require(written == bytes.size() && closed, "synth: cannot write " + path);
}

}  // namespace amos::synth
