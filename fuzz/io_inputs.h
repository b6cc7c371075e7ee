#pragma once
// What the sequence-index, trajectory and png fuzz targets do with one input, shared with their corpus replay test
// (src/amos/io/fuzz_corpus_test.cc). core::Error is the documented outcome of a malformed list; anything else
// escapes.
#include <opencv2/imgcodecs.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "amos/io/dataset.h"
#include "amos/io/png_reader.h"
#include "amos/io/trajectory.h"

namespace amos::fuzz {

// The bytes as an association file, and as rgb.txt + depth.txt: the text before the first NUL byte is rgb.txt, the
// rest depth.txt (without a NUL, the same text is both).
inline void readSequenceIndexInput(const std::string& bytes) {
  io::AssociationStats stats;
  try {
    io::parseAssociationFile(bytes, "associations.txt", 0.02, stats);
  } catch (const core::Error&) {
    // a malformed association file; the lists are read all the same
  }
  const std::size_t nul = bytes.find('\0');
  const std::string rgb = bytes.substr(0, nul);
  const std::string depth = nul == std::string::npos ? bytes : bytes.substr(nul + 1);
  io::associateFrameLists(rgb, "rgb.txt", depth, "depth.txt", 0.02);
}

// The bytes as a TUM trajectory file.
inline void readTrajectoryInput(const std::string& bytes) { io::parseTumTrajectory(bytes, "trajectory.txt"); }

// The bytes as a PNG, decoded by io::decodePng with the flags of colour and depth images. Bytes that do not start
// with PNG's signature are skipped: they would go to OpenCV's other decoders, which are not this reader. An image
// the fast path says it decoded must not be empty.
inline void decodePngInput(const std::string& bytes) {
  static constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
  if (bytes.compare(0, sizeof(kSignature) - 1, kSignature) != 0) return;
  for (const int flags : {int{cv::IMREAD_UNCHANGED}, int{cv::IMREAD_COLOR}}) {
    io::PngReadInfo info;
    const cv::Mat image =
        io::decodePng(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), flags, &info);
    if (info.route == io::PngRoute::decoded && image.empty()) throw std::logic_error("decoded to an empty image");
  }
}

}  // namespace amos::fuzz
