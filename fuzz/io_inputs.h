#pragma once
// What the sequence-index and trajectory fuzz targets do with one input, shared with their corpus replay test
// (src/amos/io/fuzz_corpus_test.cc). core::Error is the documented outcome of a malformed list; anything else
// escapes.
#include <string>

#include "amos/io/dataset.h"
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

}  // namespace amos::fuzz
