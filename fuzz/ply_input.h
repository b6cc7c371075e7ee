#pragma once
// What the ply fuzz target does with one input, shared with its corpus replay test
// (src/amos/viewer/fuzz_corpus_test.cc): the bytes are a PLY file, read as the viewer reads mesh.ply, cloud.ply
// and map.ply. core::Error is the documented outcome of a malformed file; anything else escapes.
#include <string>

#include "amos/viewer/ply_file.h"

namespace amos::fuzz {

inline void readPlyInput(const std::string& bytes) { (void)viewer::parsePly(bytes, "fuzz.ply"); }

}  // namespace amos::fuzz
