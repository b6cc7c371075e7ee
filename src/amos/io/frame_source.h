#pragma once
// The one interface the SLAM loop reads frames from, whatever delivers them: a folder read as fast as possible
// (SequenceReader), a folder replayed at its recorded rate (RealtimeReplay), a live camera
// (camera::OpenNI2Source).
//
// Thread-safety: next() and poll() are called from one consumer thread; stats() and cancel() may be called from any
// thread.
// A source that produces at its own rate (replay, camera) keeps only the newest frame waiting (NewestFrameSlot):
// a frame that arrives while an older one still waits replaces it, and the older one is counted as dropped.
// Every frame handed out has RgbdFrame::arrival set: the moment it became available to the consumer.
#include <array>
#include <cstddef>
#include <optional>

#include "amos/io/rgbd_frame.h"

namespace amos::io {

// Why a listed frame could not be used (it is skipped, or with --strict the run ends).
enum class FrameProblem {
  kMissing,     // a listed image file does not exist
  kUnreadable,  // the file exists but does not decode (truncated, not an image)
  kWrongSize,   // the image is not Camera.width x Camera.height
  kWrongFormat,  // depth that is not a single-channel 16-bit (or 32-bit float) image, e.g. an 8-bit PNG
  kBlank         // a colour image black throughout (a covered lens, a sensor not yet started)
};
constexpr std::array<FrameProblem, 5> kFrameProblems = {FrameProblem::kMissing, FrameProblem::kUnreadable,
                                                        FrameProblem::kWrongSize, FrameProblem::kWrongFormat,
                                                        FrameProblem::kBlank};
// "missing" | "unreadable" | "wrong_size" | "wrong_format" | "blank" (the keys of stats.json's "skipped_frames").
const char* frameProblemName(FrameProblem problem);

// Frames skipped, by reason.
struct SkippedFrames {
  std::array<std::size_t, kFrameProblems.size()> by_problem{};
  void add(FrameProblem problem, std::size_t n = 1) { by_problem[static_cast<std::size_t>(problem)] += n; }
  std::size_t count(FrameProblem problem) const { return by_problem[static_cast<std::size_t>(problem)]; }
  std::size_t total() const;
};

struct SourceStats {
  std::size_t delivered = 0;  // frames that became available to the consumer
  std::size_t dropped = 0;    // of those, frames replaced by a newer one before the consumer took them
  // Once the consumer has read to the end: delivered = frames it got + dropped.
  SkippedFrames skipped;      // listed frames never delivered because they could not be read
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
  // Ends the stream early (a stop request), from any thread: a next() that waits for a frame returns nullopt at
  // once, and so do later calls. For the sources whose next() can wait for long (a replay's gap in time stamps, a
  // camera that stalls); a folder, which never waits for more than one frame's decoding, ignores it.
  virtual void cancel() {}
};

}  // namespace amos::io
