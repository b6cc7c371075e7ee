#pragma once
// The libraries' decoders behind one call, chosen by the bytes' signature: PNG (libpng, png_decoder.h), JPEG
// (libjpeg, jpeg_codec.h), binary PGM/PPM (pnm_codec.h). io::readPng hands them what its fast path does not decode.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace amos::io {

// The image cv::imdecode would give, or an empty Mat with the reason in `problem` (also for other formats).
cv::Mat decodeBySignature(const std::uint8_t* data, std::size_t size, int flags, std::string& problem);

}  // namespace amos::io
