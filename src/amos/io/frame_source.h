#pragma once
// The one interface the SLAM loop reads frames from, whatever delivers them: a folder read as fast as possible
// (SequenceReader), a folder replayed at its recorded rate (RealtimeReplay), a live camera
// (camera::OpenNI2Source).
//
// Thread-safety: next() and poll() are called from one consumer thread; stats() may be called from any thread.
// A source that produces at its own rate (replay, camera) keeps only the newest frame waiting (NewestFrameSlot):
// a frame that arrives while an older one still waits replaces it, and the older one is counted as dropped.
// Every frame handed out has RgbdFrame::arrival set: the moment it became available to the consumer.
#include <cstddef>
#include <optional>

#include "amos/io/rgbd_frame.h"

namespace amos::io {

struct SourceStats {
  std::size_t delivered = 0;  // frames that became available to the consumer
  std::size_t dropped = 0;    // of those, frames replaced by a newer one before the consumer took them
  // Once the consumer has read to the end: delivered = frames it got + dropped.
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Blocks until a frame is available; nullopt at the end of the stream. Rethrows a source error (an unreadable
  // file, a lost device) in the caller's thread.
  virtual std::optional<RgbdFrame> next() = 0;
  // Does not wait: a frame that is already available, else nullopt. Sources that deliver on demand (the folder
  // reader) behave as next().
  virtual std::optional<RgbdFrame> poll() = 0;
  // Frames in the stream; 0 = unknown (live).
  virtual std::size_t size() const = 0;
  virtual SourceStats stats() const = 0;
};

}  // namespace amos::io
