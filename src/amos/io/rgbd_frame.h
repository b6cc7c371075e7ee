#pragma once
// One RGB-D frame as the SLAM loop receives it, from a folder or a live camera.
#include <opencv2/core.hpp>

#include <chrono>
#include <cstddef>
#include <string>

namespace amos::io {

struct RgbdFrame {
  std::size_t index = 0;  // position in the sequence
  double timestamp = 0;   // of the RGB image
  cv::Mat bgr;            // CV_8UC3
  cv::Mat depth;          // CV_32F metres, 0 where the sensor gave no depth
  // The sensor gave (next to) no depth for this frame (see ReaderOptions::min_valid_depth): `depth` is all zero and
  // the frame is tracked from its colour image alone.
  bool depth_dropout = false;
  std::string rgb_file;   // live frames: "<stamp>.png", a name without a file (outputs are named by its stem)
  // When the frame became available to the consumer (see frame_source.h); for the folder reader, when next()
  // handed it over.
  std::chrono::steady_clock::time_point arrival{};
};

}  // namespace amos::io
