#include "amos/io/image_codecs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "amos/core/error.h"
#include "amos/io/jpeg_codec.h"
#include "amos/io/png_encoder.h"
#include "amos/io/png_reader.h"
#include "amos/io/pnm_codec.h"

namespace amos::io {
namespace {

std::string lowerCaseWithoutDot(std::string extension) {
  if (!extension.empty() && extension.front() == '.') extension.erase(0, 1);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  core::require(file != nullptr, fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file.get()) == bytes.size();
  const int write_errno = errno;
  const bool closed = std::fclose(file.release()) == 0;  // its result says whether the bytes reached the file
  core::require(written && closed,
                fmt::format("cannot write '{}': {}", path, std::strerror(written ? errno : write_errno)));
}

}  // namespace

ImageWriteOptions jpegQuality(int quality) {
  ImageWriteOptions options;
  options.jpeg_quality = quality;
  return options;
}

ImageWriteOptions pngCompression(int level) {
  ImageWriteOptions options;
  options.png_compression = level;
  return options;
}

std::vector<std::uint8_t> encodeImage(const std::string& extension, const cv::Mat& image,
                                      const ImageWriteOptions& options) {
  const std::string format = lowerCaseWithoutDot(extension);
  if (format == "png")
    return encodePng(image, options.png_compression < 0 ? PngEncoding{} : pngEncodingForLevel(options.png_compression));
  if (format == "jpg" || format == "jpeg" || format == "jpe") return encodeJpeg(image, options.jpeg_quality);
  if (format == "pgm" || format == "ppm" || format == "pnm") return encodePnm(image);
  throw core::Error(fmt::format("no image encoder for the extension '{}' (png, jpg, jpeg, pgm, ppm, pnm)", extension));
}

void writeImage(const std::string& path, const cv::Mat& image, const ImageWriteOptions& options) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = encodeImage(std::filesystem::path(path).extension().string(), image, options);
  } catch (const core::Error& e) {
    throw core::Error(fmt::format("cannot write '{}': {}", path, e.what()));
  }
  writeBytes(path, bytes);
}

cv::Mat decodeImage(const std::vector<std::uint8_t>& bytes, int flags, std::string* problem) {
  PngReadInfo info;
  cv::Mat image = decodePng(bytes.data(), bytes.size(), flags, &info);
  if (image.empty() && problem != nullptr) *problem = info.reason;
  return image;
}

cv::Mat readImage(const std::string& path, int flags, std::string* problem) {
  if (problem == nullptr) return readPng(path, flags);
  PngReadInfo info;
  cv::Mat image = readPng(path, flags, &info);
  if (image.empty()) *problem = info.reason;
  return image;
}

}  // namespace amos::io
