#pragma once
// Reading a recorded RGB-D sequence in the TUM RGB-D / Bonn layout (rgb/ depth/ rgb.txt depth.txt, or an
// associations.txt), with the frame association `amos-slam run` uses: RGB and depth images paired by nearest time
// stamp within 20 ms, or as the association file lists them. For programs that replay such a folder through
// amos::Slam (examples/cpp/track_folder.cc); a camera program needs none of it.
//
//   amos::SequenceFolder folder("data/rgbd_dataset_freiburg2_desk");
//   while (const std::optional<amos::RgbdImages> f = folder.next()) slam.track(f->bgr, f->depth, f->timestamp);
//   if (folder.skipped() > 0) ...;   // frames that could not be read, each warned about in the log
//
// Errors (a folder that is not a sequence, a malformed list, read(i) of a frame that cannot be read, a moved-from
// folder): std::runtime_error naming the file (and line). Every member function may be called from any thread (the
// calls are serialised).
#include <opencv2/core.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

namespace amos {

// One frame of a folder, as read from its files.
struct RgbdImages {
  cv::Mat bgr;            // CV_8UC3, OpenCV's BGR order
  cv::Mat depth;          // as stored: CV_16UC1 raw values (metres = value / DepthMapFactor)
  double timestamp = 0;   // of the RGB image, seconds
  std::string rgb_file;   // the colour image's file
  std::string depth_file; // the depth image's file
};

// A TUM/Bonn-layout folder. Move-only; a moved-from folder throws std::runtime_error from every member function.
class SequenceFolder {
 public:
  // Indexes the folder (reads its lists; the images are read by read() and next()).
  explicit SequenceFolder(const std::string& dir);
  ~SequenceFolder();
  SequenceFolder(SequenceFolder&&) noexcept;
  SequenceFolder& operator=(SequenceFolder&&) noexcept;

  // The associated frames whose files exist.
  std::size_t size() const;
  // Frame i (0-based), read from its files; an unreadable frame is an error naming its file.
  RgbdImages read(std::size_t i) const;
  // The frames in order, from the first, decoded ahead by a thread of the folder's own (as `amos-slam run` reads
  // a folder), so that reading overlaps with tracking; nullopt after the last. A frame that cannot be read (missing,
  // truncated, not an image, the wrong type, its two images of different sizes) is skipped, as `amos-slam run`
  // skips it: one warning in the log naming the file and the reason, and counted in skipped(). Independent of
  // read(i).
  std::optional<RgbdImages> next();
  // Frames next() skipped so far (the frames whose files do not exist are not counted in size() at all).
  std::size_t skipped() const;
  // The sequence's ground truth file ("" when it has none).
  std::string groundTruthFile() const;
  // The folder, as given.
  std::string dir() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos
