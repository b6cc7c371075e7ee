#pragma once
// Replays a TUM/Bonn-layout folder the way the camera delivered it: at its recorded time stamps, whether or not
// the consumer keeps up. Frames are decoded ahead by a SequenceReader; a clock thread releases frame i at
// t0 + (timestamp_i - timestamp_0) on the steady clock (t0: when the first frame was decoded) into a one-frame
// "newest wins" slot, so a consumer that is still busy when the next frame is due gets the newest frame and the
// frames in between are counted as dropped (as a live camera's driver would drop them).
// Pacing waits with condition_variable::wait_until on the steady clock; nothing sleeps in a loop.
#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>

#include "amos/io/dataset.h"
#include "amos/io/frame_source.h"

namespace amos::io {

class RealtimeReplay : public FrameSource {
 public:
  // The clock starts at once: create the replay just before the loop that consumes it.
  RealtimeReplay(SequenceIndex index, ReaderOptions options);
  // Stops the clock thread (wakes it from its wait) and discards what was not taken.
  ~RealtimeReplay() override;
  RealtimeReplay(const RealtimeReplay&) = delete;
  RealtimeReplay& operator=(const RealtimeReplay&) = delete;

  // The newest released frame, waiting for the next release when none waits; nullopt after the last frame.
  // Rethrows a load error in the caller's thread.
  std::optional<RgbdFrame> next() override;
  // The newest released frame if one waits, else nullopt at once.
  std::optional<RgbdFrame> poll() override;
  std::size_t size() const override;
  SourceStats stats() const override;
  // Stops the clock at once, however long the wait for the next time stamp: next() returns nullopt.
  void cancel() override;
  // t0 of the schedule above; nullopt until the first frame has been decoded.
  std::optional<std::chrono::steady_clock::time_point> startTime() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos::io
