#include "amos/io/png_decoder.h"

#include <fmt/format.h>
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include "amos/io/exif_orientation.h"
#include "amos/io/image_read_flags.h"

namespace amos::io {
namespace {

struct MemoryInput {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t position = 0;
};

// libpng's error message, kept for the caller; a fixed buffer, since libpng leaves by longjmp.
struct ErrorMessage {
  char text[256] = {};
};

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
  auto* input = static_cast<MemoryInput*>(png_get_io_ptr(png));
  if (length > input->size - input->position) png_error(png, "truncated: the data ends early");
  std::memcpy(out, input->data + input->position, length);
  input->position += length;
}

[[noreturn]] void keepErrorAndLeave(png_structp png, png_const_charp message) {
  auto* error = static_cast<ErrorMessage*>(png_get_error_ptr(png));
  std::snprintf(error->text, sizeof error->text, "%s", message);
  png_longjmp(png, 1);
}

// libpng goes on after a warning (e.g. a bad CRC in an ancillary chunk, which it skips), as in cv::imread.
void ignoreWarning(png_structp, png_const_charp) {}

struct Header {
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, colour_type = 0;
  bool transparency = false;  // a tRNS chunk
  int orientation = 1;        // of an eXIf chunk before the image data
};

// The type OpenCV's PNG decoder reports for the file: 3 channels for RGB and palette, 4 when they have a tRNS
// chunk or an alpha channel, else 1; 16 bits for 16-bit files.
int fileType(const Header& h) {
  int channels = 1;
  if (h.colour_type == PNG_COLOR_TYPE_RGB || h.colour_type == PNG_COLOR_TYPE_PALETTE) channels = h.transparency ? 4 : 3;
  if (h.colour_type == PNG_COLOR_TYPE_GRAY_ALPHA || h.colour_type == PNG_COLOR_TYPE_RGB_ALPHA) channels = 4;
  return CV_MAKETYPE(h.bit_depth == 16 ? CV_16U : CV_8U, channels);
}

// libpng reports errors by longjmp: these functions hold no objects with destructors. False on error.
bool readHeader(png_structp png, png_infop info, Header& header) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  header.width = png_get_image_width(png, info);
  header.height = png_get_image_height(png, info);
  header.bit_depth = png_get_bit_depth(png, info);
  header.colour_type = png_get_color_type(png, info);
  header.transparency = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
#ifdef PNG_eXIf_SUPPORTED
  png_uint_32 exif_size = 0;
  png_bytep exif = nullptr;
  if (png_get_valid(png, info, PNG_INFO_eXIf) != 0 && png_get_eXIf_1(png, info, &exif_size, &exif) != 0)
    header.orientation = exifOrientation(exif, exif_size);
#endif
  return true;
}

bool readPixels(png_structp png, png_infop info, png_infop end_info, const Header& header, const cv::Mat& image,
                png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  const bool colour = image.channels() > 1;
  if (header.bit_depth == 16 && image.depth() == CV_8U) {
    png_set_strip_16(png);
  } else {
    const std::uint16_t probe = 1;
    if (*reinterpret_cast<const std::uint8_t*>(&probe) == 1) png_set_swap(png);  // PNG's samples are big-endian
  }
  if (image.channels() < 4) {
    png_set_strip_alpha(png);
  } else {
    png_set_tRNS_to_alpha(png);
  }
  if (header.colour_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  const bool file_colour = (header.colour_type & PNG_COLOR_MASK_COLOR) != 0;
  if (!file_colour && header.bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (file_colour && colour) {
    png_set_bgr(png);
  } else if (colour) {
    png_set_gray_to_rgb(png);
  } else {
    png_set_rgb_to_gray(png, PNG_ERROR_ACTION_NONE, 0.299, 0.587);
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  png_read_image(png, rows);
  png_read_end(png, end_info);
  return true;
}

struct LibpngStructs {
  png_structp png = nullptr;
  png_infop info = nullptr, end_info = nullptr;
  ~LibpngStructs() { png_destroy_read_struct(&png, &info, &end_info); }
};

}  // namespace

cv::Mat decodePngWithLibpng(const std::uint8_t* data, std::size_t size, int flags, std::string& problem) {
  MemoryInput input{data, size};
  ErrorMessage error;
  LibpngStructs s;
  s.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, keepErrorAndLeave, ignoreWarning);
  if (s.png != nullptr) s.info = png_create_info_struct(s.png);
  if (s.info != nullptr) s.end_info = png_create_info_struct(s.png);
  if (s.end_info == nullptr) {
    problem = "libpng could not allocate its structures";
    return cv::Mat();
  }
  png_set_read_fn(s.png, &input, readFromMemory);
  Header header;
  if (!readHeader(s.png, s.info, header)) {
    problem = error.text;
    return cv::Mat();
  }
  if (auto too_large = sizeProblem(header.width, header.height)) {
    problem = std::move(*too_large);
    return cv::Mat();
  }
  const std::optional<int> type = readType(flags, fileType(header));
  if (!type) {
    problem = fmt::format("unsupported read flags {}", flags);
    return cv::Mat();
  }
  cv::Mat image(static_cast<int>(header.height), static_cast<int>(header.width), *type);
  std::vector<png_bytep> rows(image.rows);
  for (int y = 0; y < image.rows; ++y) rows[y] = image.ptr(y);
  if (!readPixels(s.png, s.info, s.end_info, header, image, rows.data())) {
    problem = error.text;
    return cv::Mat();
  }
  if (appliesOrientation(flags)) applyExifOrientation(header.orientation, image);
  return image;
}

}  // namespace amos::io
