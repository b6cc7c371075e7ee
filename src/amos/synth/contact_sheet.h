#pragma once
// A contact sheet for looking at a preset: one column per frame (spread evenly over the sequence), rows with
// the colour image, the depth image (colour-mapped 0-5 m, black = no reading) and the instance mask over the
// dimmed colour image, with frame numbers and a legend of the instances.
#include <opencv2/core.hpp>

#include "amos/synth/sequence.h"

namespace amos::synth {

struct ContactSheetOptions {
  int columns = 6;       // frames shown
  int tile_width = 320;  // pixels per tile (aspect kept)
  void check() const;
};

cv::Mat contactSheet(const SequenceGenerator& generator, const ContactSheetOptions& options = {});

// Fixed colour of an instance id in overlays (0 = none).
cv::Scalar instanceColour(std::uint16_t id);

}  // namespace amos::synth
