#include "amos/io/jpeg_codec.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
// jpeglib.h needs FILE and size_t declared before it.
#include <jpeglib.h>

#include "amos/core/error.h"
#include "amos/io/exif_orientation.h"
#include "amos/io/image_read_flags.h"

namespace amos::io {
namespace {

constexpr int kApp1 = JPEG_APP0 + 1;
constexpr std::size_t kExifPrefix = 6;  // "Exif\0\0" before the TIFF block

// libjpeg's error manager, extended with the jump back and the message; libjpeg leaves by longjmp.
struct ErrorJump {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char text[JMSG_LENGTH_MAX] = {};
};

[[noreturn]] void keepErrorAndLeave(j_common_ptr info) {
  auto* error = reinterpret_cast<ErrorJump*>(info->err);
  (*info->err->format_message)(info, error->text);
  std::longjmp(error->jump, 1);
}

void ignoreMessage(j_common_ptr, int) {}  // warnings (libjpeg goes on, as in cv::imread)

jpeg_error_mgr* errorJumpManager(ErrorJump& error) {
  jpeg_error_mgr* manager = jpeg_std_error(&error.manager);
  manager->error_exit = keepErrorAndLeave;
  manager->emit_message = ignoreMessage;
  return manager;
}

int exifOrientationOf(const jpeg_decompress_struct& info) {
  for (jpeg_saved_marker_ptr marker = info.marker_list; marker != nullptr; marker = marker->next) {
    if (marker->marker == kApp1 && marker->data_length > kExifPrefix &&
        std::memcmp(marker->data, "Exif\0\0", kExifPrefix) == 0)
      return exifOrientation(marker->data + kExifPrefix, marker->data_length - kExifPrefix);
  }
  return 1;
}

// Writes why an image of this size is not decoded into error.text; false when it is decoded. Its strings are gone
// before it returns, so that it may be called between setjmp and longjmp.
bool describeSizeProblem(JDIMENSION width, JDIMENSION height, ErrorJump& error) {
  const std::optional<std::string> problem = sizeProblem(width, height);
  if (problem) std::snprintf(error.text, sizeof error.text, "%s", problem->c_str());
  return problem.has_value();
}

// libjpeg reports errors by longjmp: this function holds no objects with destructors; the image is allocated by
// the caller's `allocate`. False on error.
template <typename Allocate>
bool decode(jpeg_decompress_struct& info, ErrorJump& error, const std::uint8_t* data, std::size_t size, int flags,
            int& orientation, Allocate allocate) {
  if (setjmp(error.jump)) return false;
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, data, static_cast<unsigned long>(size));
  jpeg_save_markers(&info, kApp1, 0xffff);
  jpeg_read_header(&info, TRUE);
  if (describeSizeProblem(info.image_width, info.image_height, error)) return false;
  if (info.num_components == 4) {
    std::snprintf(error.text, sizeof error.text, "CMYK JPEGs are not supported");
    return false;
  }
  const std::optional<int> type = readType(flags, info.num_components > 1 ? CV_8UC3 : CV_8UC1);
  if (!type) {
    std::snprintf(error.text, sizeof error.text, "unsupported read flags %d", flags);
    return false;
  }
  const bool colour = CV_MAT_CN(*type) == 3;
  info.out_color_space = colour ? JCS_EXT_BGR : JCS_GRAYSCALE;
  info.out_color_components = colour ? 3 : 1;
  orientation = exifOrientationOf(info);
  jpeg_start_decompress(&info);
  cv::Mat* image = allocate(static_cast<int>(info.output_height), static_cast<int>(info.output_width), *type);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = image->ptr(static_cast<int>(info.output_scanline));
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  return true;
}

bool encode(jpeg_compress_struct& info, ErrorJump& error, const cv::Mat& image, int quality, unsigned char*& out,
            unsigned long& out_size) {
  if (setjmp(error.jump)) return false;
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, &out, &out_size);
  info.image_width = static_cast<JDIMENSION>(image.cols);
  info.image_height = static_cast<JDIMENSION>(image.rows);
  info.input_components = image.channels();
  info.in_color_space = image.channels() == 3 ? JCS_EXT_BGR : JCS_GRAYSCALE;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, quality, TRUE);  // TRUE: baseline-compatible tables, as OpenCV
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(image.ptr(static_cast<int>(info.next_scanline)));
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  return true;
}

}  // namespace

cv::Mat decodeJpeg(const std::uint8_t* data, std::size_t size, int flags, std::string& problem) {
  jpeg_decompress_struct info{};
  ErrorJump error;
  info.err = errorJumpManager(error);
  cv::Mat image;
  int orientation = 1;
  const auto allocate = [&image](int rows, int cols, int type) {
    image.create(rows, cols, type);
    return &image;
  };
  const bool ok = decode(info, error, data, size, flags, orientation, allocate);
  jpeg_destroy_decompress(&info);
  if (!ok) {
    problem = error.text;
    return cv::Mat();
  }
  if (appliesOrientation(flags)) applyExifOrientation(orientation, image);
  return image;
}

std::vector<std::uint8_t> encodeJpeg(const cv::Mat& image, int quality) {
  core::require(!image.empty() && image.depth() == CV_8U &&
                    (image.channels() == 1 || image.channels() == 3 || image.channels() == 4),
                "JPEG images must be CV_8U with 1, 3 or 4 channels, not type " + cv::typeToString(image.type()) +
                    (image.empty() ? " (empty)" : ""));
  cv::Mat input;  // a new buffer for BGR: the caller's image is const
  if (image.channels() == 4) {
    cv::cvtColor(image, input, cv::COLOR_BGRA2BGR);
  } else {
    input = image;
  }
  jpeg_compress_struct info{};
  ErrorJump error;
  info.err = errorJumpManager(error);
  unsigned char* out = nullptr;
  unsigned long out_size = 0;
  const bool ok = encode(info, error, input, std::clamp(quality, 0, 100), out, out_size);
  jpeg_destroy_compress(&info);
  std::vector<std::uint8_t> bytes;
  if (ok) bytes.assign(out, out + out_size);
  std::free(out);
  core::require(ok, std::string("libjpeg could not encode the image: ") + error.text);
  return bytes;
}

}  // namespace amos::io
