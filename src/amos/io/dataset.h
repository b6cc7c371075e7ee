#pragma once
// Reader for RGB-D sequences in the TUM RGB-D / Bonn layout:
//   rgb/ depth/ rgb.txt depth.txt [groundtruth.txt] [associations.txt | associate.txt]
// Frames are associated one-to-one by nearest timestamp within max_dt (as the TUM benchmark's associate.py
// does), or taken from an association file (`t_rgb rgb/x.png t_depth depth/y.png [...]`) when there is one, whose
// rows must go forward in time and should pair stamps within max_dt.
// Frames stream lazily through a prefetch thread, so a long sequence never sits in memory.
#include <opencv2/core.hpp>

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "amos/core/error.h"
#include "amos/io/associate.h"
#include "amos/io/frame_source.h"
#include "amos/io/rgbd_frame.h"

namespace amos::io {

struct AssociatedFrame {
  double t_rgb = 0, t_depth = 0;
  std::string rgb_file, depth_file;  // absolute or relative to the working directory
};

// How well the sequence's RGB and depth stamps pair up. Frames associated from rgb.txt + depth.txt pair only
// stamps within the window; an association file may pair any, and its rows beyond the window are counted here.
struct AssociationStats {
  std::string file;                    // the association file read; empty when rgb.txt + depth.txt were associated
  std::size_t rows = 0;                // rows of that file
  std::size_t rows_beyond_window = 0;  // rows whose RGB and depth stamps differ by more than window_s
  double window_s = 0;                 // the association window (indexSequence's max_dt)
  // rgb.txt / depth.txt rows left out for repeating the stamp of the row before (an association file's rows must
  // increase: a repeat there is an error)
  std::size_t duplicate_rows = 0;
};

struct SequenceIndex {
  std::string dir;
  std::vector<AssociatedFrame> frames;
  std::string groundtruth_file;  // empty when the sequence has none
  AssociationStats association;
  // Listed frames left out because a file of theirs does not exist: the first missing file of each.
  std::vector<std::string> missing;
};

// Lists the frames of the sequence in `dir`. Listed files that do not exist are left out (SequenceIndex::missing)
// with one warning naming them; malformed lines throw core::Error naming file and line; an empty result throws. An
// association file's RGB and depth stamps must each increase from row to row (core::Error naming file and line
// otherwise); rows whose two stamps differ by more than max_dt are kept, warned about once (count and first row)
// and counted in `association`.
SequenceIndex indexSequence(const std::string& dir, double max_dt = 0.02);

// indexSequence's reading of the lists, from their text (tests, the fuzz target): the frames of an association file
// and its stats (window max_dt), or those paired from rgb.txt and depth.txt. Files are as listed, neither joined to
// a folder nor checked; `*path` names the list in errors. Throws core::Error as indexSequence does.
std::vector<AssociatedFrame> parseAssociationFile(const std::string& text, const std::string& path, double max_dt,
                                                  AssociationStats& stats);
std::vector<AssociatedFrame> associateFrameLists(const std::string& rgb_text, const std::string& rgb_path,
                                                 const std::string& depth_text, const std::string& depth_path,
                                                 double max_dt);

struct ReaderOptions {
  double depth_factor = 5000.0;  // DepthMapFactor: raw 16-bit value / factor = metres
  int width = 640, height = 480; // expected image size (Camera.width/height)
  std::size_t prefetch = 8;      // frames decoded ahead of the consumer
  // A depth image with fewer valid pixels than this share is a sensor dropout (RgbdFrame::depth_dropout): its depth
  // is cleared and the frame is tracked from colour alone. 1 % is 3072 pixels at 640x480: too few to initialise a
  // map (Tracking.initMinDepthPoints keypoints with depth) or to anchor new map points, and far below any real frame
  // here (TUM fr2 desk: 63 % at least, Bonn crowd: 81 %), so only a sensor that gave up is caught.
  double min_valid_depth = 0.01;
  // --strict: a frame that cannot be read (FrameLoadError) or a listed file that is missing ends the stream with
  // that error; by default such a frame is skipped with a warning and counted (SourceStats::skipped).
  bool strict = false;
};

// A frame that cannot be used: the reason and the file at fault (named in the message too).
class FrameLoadError : public core::Error {
 public:
  FrameLoadError(FrameProblem problem, std::string file, const std::string& message)
      : core::Error(message), problem_(problem), file_(std::move(file)) {}
  FrameProblem problem() const { return problem_; }
  const std::string& file() const { return file_; }

 private:
  FrameProblem problem_;
  std::string file_;
};

// Loads and validates one frame: throws FrameLoadError naming the file for a missing or unreadable image, a wrong
// size, a blank colour image (black throughout: nothing to track) or a depth image that is not 16-bit
// single-channel. A depth dropout (see ReaderOptions::min_valid_depth) is
// not an error: the frame comes back with depth_dropout set and all-zero depth.
RgbdFrame loadRgbdFrame(const AssociatedFrame& entry, const ReaderOptions& options, std::size_t index);
// loadRgbdFrame's checks and conversion on images already in memory (the library API's frames): `bgr` CV_8UC3,
// `raw_depth` CV_16U (raw, scaled by 1 / depth_factor) or CV_32F (metres); `entry` names them in errors and gives
// the time stamp (t_rgb). The depth is always a new buffer; `bgr` is kept as given (the caller copies it when its
// pixels may change).
RgbdFrame rgbdFrameFromImages(const AssociatedFrame& entry, cv::Mat bgr, const cv::Mat& raw_depth,
                              const ReaderOptions& options, std::size_t index);

// Reads a folder as fast as the consumer takes the frames (the default source), decoding `prefetch` frames ahead
// in its own thread. Delivers on demand: nothing is ever dropped, and poll() is next(). A frame that cannot be
// read is skipped with one warning naming the file and the reason, and counted in stats().skipped (the frames the
// index left out as missing included); with ReaderOptions::strict the first one is an error instead.
class SequenceReader : public FrameSource {
 public:
  // How a listed frame is read, in the reader's thread: loadRgbdFrame (files), or a recording's own reader (a ROS
  // bag's messages, src/amos/rosbag) that throws FrameLoadError as it does.
  using FrameLoader = std::function<RgbdFrame(const AssociatedFrame&, const ReaderOptions&, std::size_t)>;
  SequenceReader(SequenceIndex index, ReaderOptions options, FrameLoader loader = loadRgbdFrame);
  ~SequenceReader() override;
  SequenceReader(const SequenceReader&) = delete;
  SequenceReader& operator=(const SequenceReader&) = delete;

  // Next frame in order, or nullopt at the end. Rethrows a load error in the caller's thread (with strict, or an
  // error that is not a FrameLoadError).
  std::optional<RgbdFrame> next() override;
  std::optional<RgbdFrame> poll() override { return next(); }
  std::size_t size() const override;
  SourceStats stats() const override;
  const SequenceIndex& index() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos::io
