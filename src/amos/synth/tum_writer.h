#pragma once
// Writes a synthetic sequence in the TUM RGB-D layout (what io::indexSequence reads), plus its extra ground
// truth: rgb/ and depth/ PNGs (depth 16-bit, metres * 5000), masks/ (16-bit PNG, 0 = static, otherwise the
// instance id), rgb.txt / depth.txt / masks.txt (`timestamp folder/<stamp>.png` with '#' headers),
// associations.txt (`t_rgb rgb/.. t_depth depth/..`), groundtruth.txt (`timestamp tx ty tz qx qy qz qw`, T_wc)
// and instances.json (id -> class, name, frame ranges where it moves; plus the generator's settings).
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "amos/synth/sequence.h"

namespace amos::synth {

// "1700000000.033333": the file stem and time stamp text of a frame.
std::string formatTimestamp(double t);

class TumWriter {
 public:
  // Creates the folders and index files; throws core::Error when output_dir cannot be written.
  TumWriter(const std::string& output_dir, const SequenceGenerator& generator);
  void add(const SyntheticFrame& frame);
  // Writes instances.json and flushes the index files.
  void finish();

 private:
  std::string dir_;
  const SequenceGenerator& generator_;
  std::ofstream rgb_, depth_, masks_, assoc_, gt_;
  std::map<std::uint16_t, std::vector<std::pair<int, int>>> moving_ranges_;
  int frames_ = 0;
};

}  // namespace amos::synth
