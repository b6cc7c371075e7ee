#pragma once
// PNG files for the sequence writer, encoded by io::encodePng (libpng) with a fixed row filter: libpng's
// adaptive choice (what cv::imwrite does) tries all five filters on every row and was a third of the time per
// frame. Paeth for colour and Up for depth and masks, zlib level 1 with run-length matching: as small as the
// adaptive choice on these noisy images, at about two thirds of the time.
#include <opencv2/core.hpp>
#include <string>

namespace amos::synth {

// image: CV_8UC3 (BGR), CV_8UC1 or CV_16UC1. Throws core::Error when the file cannot be written.
void writePng(const std::string& path, const cv::Mat& image);

}  // namespace amos::synth
