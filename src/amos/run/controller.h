#pragma once
// The run loop as a controller (after COLMAP's BaseController): a short loop that reads frames from a source,
// pushes them through the pipeline, tells the observers about each processed frame and checks for a stop; every
// other step of a run (what is made of a frame: evaluation, mask scoring, writing, recording, the viewer) lives in
// an observer (run_observer.h), and the run's set-up and end in sequence_run.cc.
//
// With a folder the next frame is always pushed into the pipeline's stage A while the current one is in stage B
// (one frame of look-ahead, system/dynamic_pipeline.h); with a paced or live source a feeder thread pushes each
// frame into stage A as soon as stage A is free (paced_feeder.h).
#include <cstddef>
#include <exception>
#include <functional>
#include <vector>

#include "amos/core/stage_timer.h"
#include "amos/core/stop_request.h"
#include "amos/io/frame_source.h"
#include "amos/report/run_report.h"
#include "amos/run/run_observer.h"
#include "amos/system/dynamic_pipeline.h"

namespace amos::run {

struct SequenceProgress {
  std::size_t frame = 0, total = 0;  // frame: 1-based position of the processed frame in the stream; total 0 = live
  std::size_t processed = 0;         // frames processed so far, this one included
  const system::FrameOutput* output = nullptr;
  double elapsed_s = 0;
};

struct ControllerOptions {
  bool paced = false;          // a paced or live source (a feeder thread) instead of a folder read at once
  std::size_t max_frames = 0;  // end after this many processed frames (0 = when the source ends)
  // When set, the loop ends after the frame being processed once a stop is requested; with a paced or live source
  // the request also ends the wait for the next frame at once (FrameSource::cancel), whatever the time stamps.
  core::StopRequest* stop = nullptr;
  std::function<void(const SequenceProgress&)> on_frame;  // after every frame, after the observers (progress)
};

// What the loop leaves for the end of the run.
struct LoopOutcome {
  std::size_t processed = 0;
  bool interrupted = false;     // the stop flag ended it
  std::exception_ptr failure;   // the error that ended it (the loop's own first, else the source's), or null
  double outputs_ms = 0;        // time in the observers added as outputs (kept out of the run's wall time)
  std::vector<double> latency_ms;  // per processed frame: from its arrival to its pose
  report::DepthDropouts depth_dropouts;
};

class RunController {
 public:
  // Not owned; they must outlive the controller. The run's clock starts here.
  RunController(io::FrameSource& source, system::DynamicPipeline& pipeline, ControllerOptions options);

  // Observers are called in the order they are added. `output`: its onFrame time counts as outputs time (mask
  // scoring and writing), not as the run's.
  void addObserver(RunObserver& observer, bool output = false);
  const std::vector<RunObserver*>& observers() const { return observers_; }

  void notifyStart(const RunStart& start);
  // The loop. An error in it (a stage-A lane's failure, a source error after the frames it delivered) ends it like
  // a stop does; it is returned in LoopOutcome::failure, not thrown.
  LoopOutcome run();
  // Milliseconds since the controller was made, without the outputs time.
  double runMs() const { return wall_.elapsedMs() - outcome_.outputs_ms; }

 private:
  bool stopRequested();
  void feed();
  // Everything done with a processed frame; false when the run should end (--max-frames reached).
  bool consume(const system::ProcessedFrame& out);
  void notifyFrame(const system::ProcessedFrame& out);

  io::FrameSource& source_;
  system::DynamicPipeline& pipeline_;
  ControllerOptions options_;
  std::vector<RunObserver*> observers_;
  std::vector<bool> output_;  // per observer: added as an output
  core::Stopwatch wall_;
  double last_frame_ms_ = 0;  // wall_.elapsedMs() when the previous frame was done
  std::exception_ptr source_failure_;
  LoopOutcome outcome_;
};

}  // namespace amos::run
