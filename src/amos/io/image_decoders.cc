#include "amos/io/image_decoders.h"

#include <cstring>

#include "amos/io/jpeg_codec.h"
#include "amos/io/png_decoder.h"
#include "amos/io/pnm_codec.h"

namespace amos::io {

cv::Mat decodeBySignature(const std::uint8_t* data, std::size_t size, int flags, std::string& problem) {
  static constexpr std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static constexpr std::uint8_t kJpeg[3] = {0xff, 0xd8, 0xff};
  if (size >= sizeof kPng && std::memcmp(data, kPng, sizeof kPng) == 0)
    return decodePngWithLibpng(data, size, flags, problem);
  if (size >= sizeof kJpeg && std::memcmp(data, kJpeg, sizeof kJpeg) == 0)
    return decodeJpeg(data, size, flags, problem);
  if (looksLikePnm(data, size)) return decodePnm(data, size, flags, problem);
  problem = "not a PNG, JPEG, PGM or PPM image";
  return cv::Mat();
}

}  // namespace amos::io
