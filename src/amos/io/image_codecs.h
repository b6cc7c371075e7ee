#pragma once
// The project's image files, in place of OpenCV's imgcodecs (whose Debian build loads GDAL, VTK and a hundred more
// libraries into every process): cv::imread / imwrite / imencode / imdecode for the formats the project uses, with
// their flags (image_read_flags.h) and results.
//   PNG   8-bit grey, BGR, BGRA; 16-bit grey (depth), BGR, BGRA: libpng, byte for byte cv::imencode's files
//   JPEG  8-bit grey, BGR (BGRA written without alpha): libjpeg-turbo, as OpenCV sets it up
//   PGM / PPM (binary P5 / P6) 8 or 16 bits, grey or BGR: the occupancy grid's format
// Reading decodes by the bytes' signature, not the file name; writing encodes in the format the extension names.
#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "amos/io/image_read_flags.h"

namespace amos::io {

struct ImageWriteOptions {
  int jpeg_quality = 95;  // 0 to 100, as cv::IMWRITE_JPEG_QUALITY (default 95)
  // As cv::IMWRITE_PNG_COMPRESSION: -1 for cv::imwrite's default (Sub row filter, zlib level 1, run-length
  // matching), 0 to 9 for that zlib level with libpng's adaptive row filters.
  int png_compression = -1;
};

// Options with one setting changed, as cv::imencode's {cv::IMWRITE_JPEG_QUALITY, q} / {cv::IMWRITE_PNG_COMPRESSION, l}.
ImageWriteOptions jpegQuality(int quality);
ImageWriteOptions pngCompression(int level);

// The image encoded in the format `extension` names (".png", ".jpg"/".jpeg", ".pgm"/".ppm"/".pnm"; the dot and
// case optional). Throws core::Error for another extension or an image type the format does not hold.
std::vector<std::uint8_t> encodeImage(const std::string& extension, const cv::Mat& image,
                                      const ImageWriteOptions& options = {});

// Encodes `image` in the format of the path's extension and writes it. Throws core::Error naming the file when it
// cannot be encoded or written.
void writeImage(const std::string& path, const cv::Mat& image, const ImageWriteOptions& options = {});

// The image the bytes hold (cv::imdecode), or an empty Mat when they are not one of the formats above or are
// corrupt; `problem`, when given, then receives why.
cv::Mat decodeImage(const std::vector<std::uint8_t>& bytes, int flags, std::string* problem = nullptr);

// The image in the file (cv::imread), or an empty Mat when it is missing, unreadable or not an image; `problem`,
// when given, then receives why (else a warning naming the file is logged).
cv::Mat readImage(const std::string& path, int flags, std::string* problem = nullptr);

}  // namespace amos::io
