#pragma once
// Reader for RGB-D sequences in the TUM RGB-D / Bonn layout:
//   rgb/ depth/ rgb.txt depth.txt [groundtruth.txt] [associations.txt | associate.txt]
// Frames are associated one-to-one by nearest timestamp within max_dt (as the TUM benchmark's associate.py
// does), or taken from an association file (`t_rgb rgb/x.png t_depth depth/y.png [...]`) when there is one, whose
// rows must go forward in time and should pair stamps within max_dt.
// Frames stream lazily through a prefetch thread, so a long sequence never sits in memory.
#include <opencv2/core.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

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
};

struct SequenceIndex {
  std::string dir;
  std::vector<AssociatedFrame> frames;
  std::string groundtruth_file;  // empty when the sequence has none
  AssociationStats association;
};

// Lists the frames of the sequence in `dir`. Listed files that do not exist are skipped with one warning naming
// them; malformed lines throw core::Error naming file and line; an empty result throws. An association file's RGB
// and depth stamps must each increase from row to row (core::Error naming file and line otherwise); rows whose two
// stamps differ by more than max_dt are kept, warned about once (count and first row) and counted in
// `association`.
SequenceIndex indexSequence(const std::string& dir, double max_dt = 0.02);

struct ReaderOptions {
  double depth_factor = 5000.0;  // DepthMapFactor: raw 16-bit value / factor = metres
  int width = 640, height = 480; // expected image size (Camera.width/height)
  std::size_t prefetch = 8;      // frames decoded ahead of the consumer
};

// Loads and validates one frame: throws core::Error naming the file for unreadable images, a wrong size,
// an 8-bit depth image or a depth image without a single valid pixel.
RgbdFrame loadRgbdFrame(const AssociatedFrame& entry, const ReaderOptions& options, std::size_t index);

// Reads a folder as fast as the consumer takes the frames (the default source), decoding `prefetch` frames ahead
// in its own thread. Delivers on demand: nothing is ever dropped, and poll() is next().
class SequenceReader : public FrameSource {
 public:
  SequenceReader(SequenceIndex index, ReaderOptions options);
  ~SequenceReader() override;
  SequenceReader(const SequenceReader&) = delete;
  SequenceReader& operator=(const SequenceReader&) = delete;

  // Next frame in order, or nullopt at the end. Rethrows a load error of that frame in the caller's thread.
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
