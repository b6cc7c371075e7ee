#pragma once
// Real imagery the user may point the generator to: photographs for posters, pictures and screens, and person
// cut-outs (RGB + mask) that dress the people so that a real person detector finds them. This is the only
// part of the synth module that reads files (besides the writer); everything else is drawn.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace amos::synth {

struct PersonCutout {
  enum class Kind {
    kStanding,   // a whole standing person
    kUpperBody,  // a standing person cut by the photo's bottom border: gets procedural legs
    kSitting,    // a whole seated person
  };
  cv::Mat bgr;    // CV_8UC3, the person's bounding box
  cv::Mat alpha;  // CV_8UC1, 255 inside the person
  Kind kind = Kind::kStanding;
  double visible_fraction = 1.0;  // estimated part of the standing height shown, from the top of the head
  cv::Scalar lower_colour;        // mean colour of the lowest visible rows (trousers)
  std::string source;             // file it came from
};

// Person cut-outs in one photo: each connected region of mask (CV_8UC1, > 127 = person) of at least 1.5% of
// the image that does not touch the left, right or top border. Regions less than 2.1 times as tall as wide are
// taken as seated people (their feet may touch the bottom border); taller ones touching the bottom border are
// kUpperBody, the others kStanding.
std::vector<PersonCutout> extractCutouts(const cv::Mat& bgr, const cv::Mat& mask, const std::string& source);

// All cut-outs of a folder laid out as <dir>/rgb/NAME and <dir>/mask/NAME (as ../shared/data/person_masks).
// Throws core::Error when the folder has no usable cut-out.
std::vector<PersonCutout> loadPersonCutouts(const std::string& dir);

// Up to max_count 8-bit colour photographs found under dir (recursively, .png/.jpg/.jpeg, sorted by path,
// evenly spaced through the list), skipping folders named depth, mask or masks; resized to at most 640 px wide.
// Throws core::Error when none is found.
std::vector<cv::Mat> loadPhotos(const std::string& dir, std::size_t max_count = 16);

}  // namespace amos::synth
