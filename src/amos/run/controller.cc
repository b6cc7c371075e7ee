#include "amos/run/controller.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <optional>
#include <utility>

#include "amos/report/frame_log.h"
#include "amos/run/paced_feeder.h"

namespace amos::run {

namespace {

// What observers see of a processed frame: image headers are shared, the keypoints copied.
FrameSnapshot frameSnapshot(const system::ProcessedFrame& out, std::size_t total, std::size_t processed) {
  FrameSnapshot s;
  s.index = out.frame.index;
  s.total = total;
  s.processed = processed;
  s.timestamp = out.frame.timestamp;
  s.rgb_file = out.frame.rgb_file;
  s.state = out.slam.track.state;
  s.T_cw = out.slam.track.T_cw;
  s.new_keyframe = out.slam.track.new_keyframe;
  s.inliers = out.slam.track.inliers;
  s.bgr = out.frame.bgr;
  s.dynamic_mask = out.dynamic_mask;
  s.prior_mask = out.prior_mask;
  s.keypoints = out.keypoints;
  s.keypoints_removed = out.slam.removed_dynamic;
  s.extract_ms = out.slam.extract_ms;
  s.build_ms = out.slam.build_ms;
  s.track_ms = out.slam.track_ms;
  s.frame = out.frame;
  return s;
}

double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

RunController::RunController(io::FrameSource& source, system::DynamicPipeline& pipeline, ControllerOptions options)
    : source_(source), pipeline_(pipeline), options_(std::move(options)) {}

void RunController::addObserver(RunObserver& observer, bool output) {
  observers_.push_back(&observer);
  output_.push_back(output);
}

void RunController::notifyStart(const RunStart& start) {
  for (RunObserver* o : observers_) o->onStart(start);
}

LoopOutcome RunController::run() {
  wall_.restart();
  try {
    if (options_.paced) {
      // A feeder thread hands frames to stage A as they arrive (paced_feeder.h).
      PacedFeeder feeder(source_, pipeline_);
      // A stop wakes the feeder's wait and the source's at once (a replay may wait minutes for a late time stamp).
      core::StopRequest::Subscription wake;
      if (options_.stop != nullptr) {
        wake = options_.stop->onStop([&] {
          feeder.stop();
          source_.cancel();
        });
      }
      while (!stopRequested() && feeder.nextForStageB())
        if (!consume(pipeline_.processNext())) break;
    } else {
      // One frame of look-ahead: stage A of frame k+1 runs while frame k is in stage B.
      feed();
      while (pipeline_.waiting() > 0 && !stopRequested()) {
        if (pipeline_.waiting() < 2) feed();
        if (!consume(pipeline_.processNext())) break;
      }
    }
  } catch (...) {
    outcome_.failure = std::current_exception();
  }
  if (!outcome_.interrupted) stopRequested();  // a stop that ended a paced source's wait
  if (!outcome_.failure) outcome_.failure = source_failure_;
  return outcome_;
}

bool RunController::stopRequested() {
  outcome_.interrupted = options_.stop != nullptr && options_.stop->requested();
  return outcome_.interrupted;
}

// Pushes the source's next frame into the pipeline's stage A (folder). A source error (a frame that cannot be read
// with --strict) ends the stream: the frames already pushed are still processed, then the run ends with that error.
void RunController::feed() {
  if (source_failure_) return;
  std::optional<io::RgbdFrame> f;
  try {
    f = source_.next();
  } catch (...) {
    source_failure_ = std::current_exception();
  }
  if (f) pipeline_.push(std::move(*f));
}

bool RunController::consume(const system::ProcessedFrame& out) {
  const io::RgbdFrame& frame = out.frame;
  outcome_.latency_ms.push_back(msSince(frame.arrival));
  if (options_.paced)
    spdlog::debug("frame {}: {:.1f} ms from arrival to pose", frame.index, outcome_.latency_ms.back());
  ++outcome_.processed;
  report::countDepthDropout(out, outcome_.depth_dropouts);
  notifyFrame(out);
  if (options_.on_frame)
    options_.on_frame({frame.index + 1, source_.size(), outcome_.processed, &out.slam, runMs() / 1000.0});
  return options_.max_frames == 0 || outcome_.processed < options_.max_frames;  // a live source has no end of its own
}

void RunController::notifyFrame(const system::ProcessedFrame& out) {
  FrameSnapshot snapshot = frameSnapshot(out, source_.size(), outcome_.processed);
  const double now_ms = wall_.elapsedMs();
  snapshot.frame_ms = now_ms - last_frame_ms_;
  snapshot.elapsed_s = now_ms / 1000.0;
  last_frame_ms_ = now_ms;
  for (std::size_t i = 0; i < observers_.size(); ++i) {
    core::Stopwatch watch;
    observers_[i]->onFrame(snapshot);
    if (output_[i]) outcome_.outputs_ms += watch.elapsedMs();
  }
}

}  // namespace amos::run
