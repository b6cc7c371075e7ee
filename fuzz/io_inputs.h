#pragma once
// What the sequence-index, trajectory and png fuzz targets do with one input, shared with their corpus replay test
// (src/amos/io/fuzz_corpus_test.cc). core::Error is the documented outcome of a malformed list; anything else
// escapes.
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

// The bytes as an image, decoded by io::decodePng with the flags of colour and depth images: PNGs by its fast path
// or libpng, other bytes by the JPEG and PGM/PPM decoders (image_decoders.h). An image decoded by either route must
// not be empty (a failure is the route "rejected").
inline void decodePngInput(const std::string& bytes) {
  for (const int flags : {io::kReadUnchanged, io::kReadColor}) {
    io::PngReadInfo info;
    const cv::Mat image =
        io::decodePng(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), flags, &info);
    if (info.route != io::PngRoute::rejected && image.empty()) throw std::logic_error("decoded to an empty image");
  }
}

}  // namespace amos::fuzz
