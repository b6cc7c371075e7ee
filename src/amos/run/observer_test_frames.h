#pragma once
// Test support for the observers' unit tests: FrameSnapshots made from a short synthetic sequence's frames, as the
// controller makes them, without running SLAM.
#include <filesystem>
#include <string>
#include <vector>

#include "amos/io/dataset.h"
#include "amos/run/run_observer.h"
#include "amos/synth/sequence.h"

namespace amos::run::testing {

// A synthetic sequence (preset, seed 1, `frames` frames) rendered once into the build folder's cache.
inline std::string syntheticSequence(const std::string& preset, int frames) {
  return synth::cachedSequence((std::filesystem::path(AMOS_BINARY_DIR) / "test_outputs" / "synth_cache").string(),
                               preset, 1, frames);
}

// Every frame of `sequence_dir` as the controller shows it to observers (no dynamic mask: set one to test).
inline std::vector<FrameSnapshot> snapshotsOf(const std::string& sequence_dir) {
  const io::SequenceIndex index = io::indexSequence(sequence_dir);
  io::ReaderOptions reader;
  std::vector<FrameSnapshot> out;
  for (std::size_t i = 0; i < index.frames.size(); ++i) {
    FrameSnapshot s;
    s.frame = io::loadRgbdFrame(index.frames[i], reader, i);
    s.index = i;
    s.total = index.frames.size();
    s.processed = i + 1;
    s.timestamp = s.frame.timestamp;
    s.rgb_file = s.frame.rgb_file;
    s.bgr = s.frame.bgr;
    out.push_back(s);
  }
  return out;
}

}  // namespace amos::run::testing
