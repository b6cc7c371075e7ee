#pragma once
// Feeding the pipeline from a paced source (a folder replayed at its recorded rate, a live camera), which
// delivers frames at its own rate. The feeder's thread hands each frame to the pipeline's stage A as soon as
// stage A is free, i.e. when no pushed frame waits for stage B besides the one stage B works on. So stage A of
// frame k+1 runs beside stage B of frame k, as it does with a folder, and a frame that arrives while stage A is
// still occupied waits in the source's newest-wins slot, where a newer one replaces it (the source counts it as
// dropped). Without the feeder the loop could only look for a waiting frame between two frames, and stage A of a
// frame that arrived during stage B would start only after it: A and B one after the other on every frame.
//
//   PacedFeeder feeder(source, pipeline);  // starts the thread
//   while (feeder.nextForStageB()) {
//     ProcessedFrame out = pipeline.processNext();
//     ...
//   }
//
// Thread safety: nextForStageB() is called from the thread that runs stage B; stop() from any thread (a stop
// request).
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>

#include "amos/io/frame_source.h"
#include "amos/system/dynamic_pipeline.h"

namespace amos::run {

class PacedFeeder {
 public:
  PacedFeeder(io::FrameSource& source, system::DynamicPipeline& pipeline);
  // Stops feeding and joins the thread (which may first wait for the source's next frame: at most one period).
  ~PacedFeeder();
  PacedFeeder(const PacedFeeder&) = delete;
  PacedFeeder& operator=(const PacedFeeder&) = delete;

  // Blocks until a pushed frame waits for stage B (true: the caller processes it next), the stream has ended or
  // stop() was called (false). Rethrows what ended the feeding in error (a source error, a refused push).
  bool nextForStageB();
  // The thread pushes no frame after the one it may be pushing now, and nextForStageB() returns false; the
  // destructor joins the thread (cancel the source first when its next() may wait long). Idempotent.
  void stop();

 private:
  void run();

  io::FrameSource& source_;
  system::DynamicPipeline& pipeline_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::size_t pushed_ = 0, taken_ = 0;  // frames pushed into stage A, and taken by stage B
  bool ended_ = false;                 // the source has no more frames, or the feeding failed
  bool stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: started once the rest exists
};

}  // namespace amos::run
