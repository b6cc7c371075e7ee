#pragma once
// Test bags: short synthetic sequences rendered once per test binary and written as bags (bag_writer.h), and bags
// written message by message for the malformed cases.
#include <filesystem>
#include <string>

#include "amos/config/settings.h"
#include "amos/io/dataset.h"
#include "amos/rosbag/bag_writer.h"
#include "amos/synth/sequence.h"
#include "amos/testing/scratch_dir.h"

namespace amos::rosbag::test {

// A synthetic walking_static sequence of `frames` frames in <scratch>/<name>/ (rendered once per process and name).
inline std::string syntheticSequence(const std::string& name, int frames) {
  static std::filesystem::path root = testing::scratchDir("amos_rosbag_sequences");
  const std::filesystem::path dir = root / name;
  if (!std::filesystem::exists(dir / "rgb.txt")) {
    synth::SequenceOptions options;
    options.preset = "walking_static";
    options.seed = 1;
    options.frames = frames;
    synth::renderSequence(options, dir.string());
  }
  return dir.string();
}

const std::string kTum3 = std::string(AMOS_SOURCE_DIR) + "/configs/tum3.yaml";
const std::string kTum2 = std::string(AMOS_SOURCE_DIR) + "/configs/tum2.yaml";

// The calibration the synthetic sequences are rendered with (configs/tum3.yaml's), for camera_info messages.
inline core::CameraIntrinsics syntheticCamera() { return config::loadSettings(kTum3).camera; }

// `sequence` written to <dir>/<name> with `options` (the synthetic camera's camera_info unless options say).
inline std::string writeTestBag(const std::string& sequence, const std::filesystem::path& dir, const std::string& name,
                                BagWriteOptions options = {}) {
  if (!options.camera) options.camera = syntheticCamera();
  const std::string bag = (dir / name).string();
  writeBag(io::indexSequence(sequence), bag, options);
  return bag;
}

}  // namespace amos::rosbag::test
