#pragma once
// Reading a recorded RGB-D sequence in the TUM RGB-D / Bonn layout (rgb/ depth/ rgb.txt depth.txt, or an
// associations.txt), with the frame association `amos-slam run` uses: RGB and depth images paired by nearest time
// stamp within 20 ms, or as the association file lists them. For programs that replay such a folder through
// amos::Slam (examples/cpp/track_folder.cc); a camera program needs none of it.
//
//   amos::SequenceFolder folder("data/rgbd_dataset_freiburg2_desk");
//   while (const std::optional<amos::RgbdImages> f = folder.next()) slam.track(f->bgr, f->depth, f->timestamp);
//
// Errors (a folder that is not a sequence, a malformed list, an image that cannot be read): std::runtime_error
// naming the file (and line).
#include <opencv2/core.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

namespace amos {

struct RgbdImages {
  cv::Mat bgr;            // CV_8UC3, OpenCV's BGR order
  cv::Mat depth;          // as stored: CV_16U raw values (metres = value / DepthMapFactor)
  double timestamp = 0;   // of the RGB image, seconds
  std::string rgb_file, depth_file;
};

class SequenceFolder {
 public:
  explicit SequenceFolder(const std::string& dir);
  ~SequenceFolder();
  SequenceFolder(SequenceFolder&&) noexcept;
  SequenceFolder& operator=(SequenceFolder&&) noexcept;

  std::size_t size() const;  // associated frames
  // Frame i (0-based), read from its files.
  RgbdImages read(std::size_t i) const;
  // The frames in order, from the first, decoded ahead by a thread of the folder's own (as `amos-slam run` reads
  // a folder), so that reading overlaps with tracking; nullopt after the last. A frame that cannot be read throws
  // here, in its turn. Independent of read(i).
  std::optional<RgbdImages> next();
  // The sequence's ground truth file ("" when it has none).
  std::string groundTruthFile() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos
