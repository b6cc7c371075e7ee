#include "amos/synth/png_writer.h"

#include <cstdio>
#include <vector>

#include "amos/core/error.h"
#include "amos/io/png_encoder.h"

namespace amos::synth {

void writePng(const std::string& path, const cv::Mat& image) {
  core::require(!image.empty() && (image.type() == CV_8UC3 || image.type() == CV_8UC1 || image.type() == CV_16UC1),
                "synth: PNG images must be CV_8UC3, CV_8UC1 or CV_16UC1 (" + path + ")");
  io::PngEncoding encoding;
  encoding.filter = image.channels() == 3 ? io::PngEncoding::Filter::paeth : io::PngEncoding::Filter::up;
  const std::vector<std::uint8_t> bytes = io::encodePng(image, encoding);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  core::require(f != nullptr, "synth: cannot write " + path);
  const std::size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
  const bool closed = std::fclose(f) == 0;
  core::require(written == bytes.size() && closed, "synth: cannot write " + path);
}

}  // namespace amos::synth
