#pragma once
// `amos-slam run --record DIR`: writes the frames a run received in the TUM RGB-D layout, so a live session can be
// replayed (`--sequence DIR`, with or without `--realtime`) and evaluated later:
//   rgb/<stamp>.png    the colour image as received (8-bit BGR, lossless)
//   depth/<stamp>.png  the depth in 16 bits at the settings' depth factor (raw = round(metres * factor); no depth,
//                      NaN and depths beyond the 16-bit range are written as 0)
//   rgb.txt, depth.txt `timestamp filename`, the time stamp written so that it reads back to the same double
// <stamp> is the time stamp with six decimals (TUM's own naming) when that reads back exactly, else with as many
// digits as it takes. Read back by indexSequence + loadRgbdFrame, colour is bit-identical, and so is depth that is
// a multiple of 1 / factor (any depth read from a 16-bit PNG at the same factor).
// The PNGs are encoded by a writer thread, so the SLAM loop only queues a frame (its images are shared, not
// copied: do not write into them after add()).
#include <cstddef>
#include <memory>
#include <string>

#include "amos/io/rgbd_frame.h"

namespace amos::io {

// The text a time stamp is written as (see above).
std::string stampText(double timestamp);

class SequenceRecorder {
 public:
  // Creates dir/, dir/rgb and dir/depth (an existing recording there is overwritten frame by frame and its lists
  // replaced). Throws core::Error naming the folder or file that cannot be written.
  SequenceRecorder(const std::string& dir, double depth_factor, std::size_t queue_capacity = 32);
  // Finishes when finish() was not called; a write error is then logged, not thrown.
  ~SequenceRecorder();
  SequenceRecorder(const SequenceRecorder&) = delete;
  SequenceRecorder& operator=(const SequenceRecorder&) = delete;

  // Queues `frame` for writing; blocks while queue_capacity frames wait. A frame with the same time stamp text as
  // the one before is skipped with a warning (its files would overwrite that one's). Rethrows the first write
  // error of an earlier frame.
  void add(const RgbdFrame& frame);
  // Writes every queued frame and closes the lists; rethrows the first write error. add() is not allowed after.
  void finish();
  std::size_t framesWritten() const;
  const std::string& dir() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos::io
