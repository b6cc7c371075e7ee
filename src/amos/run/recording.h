#pragma once
// Recording (`amos-slam run --record DIR`) as an observer: every processed frame, as the source delivered it, into
// DIR in TUM layout (io/sequence_recorder.h), to replay and evaluate later.
#include <string>

#include "amos/io/sequence_recorder.h"
#include "amos/run/run_observer.h"

namespace amos::run {

class Recording : public RunObserver {
 public:
  // Creates DIR (io::SequenceRecorder; throws core::Error naming what cannot be written).
  Recording(const std::string& dir, double depth_factor);

  void onFrame(const FrameSnapshot& frame) override { recorder_.add(frame.frame); }
  // Writes the queued frames and closes the lists; rethrows the first write error.
  void onStreamEnd() override { recorder_.finish(); }

  std::size_t framesWritten() const { return recorder_.framesWritten(); }

 private:
  io::SequenceRecorder recorder_;
};

}  // namespace amos::run
