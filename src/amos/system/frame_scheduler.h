#pragma once
// Stage A of the pipeline (dynamic_pipeline.h): the per-frame work that needs nothing but the frame, scheduled
// ahead into frame slots as soon as a frame is pushed. The tasks a mode schedules (StageATasks::forMode):
//   none      motion (grey image only), features (ORB)
//   prior     + segmentation (the person networks) on the frames Dynamic.Prior.* names: the detector and the mask
//               network on every detectEvery-th of them, the mask network alone on the boxes of the last one on
//               the others (a dependency on that earlier segmentation, met by the lane's order)
//   geometry  motion with the LK pyramid and corners, features, partition (superpixels + clusters, Sec. III-B)
//   full      all of them
// Lanes, each a core::SerialExecutor running its tasks in push order:
//   segmentation lane   segmentation(k)                     (the segmentation worker's)
//   frame lane          motion(k), corner tracks(k), then features(k)
//                       (tracks read motion(k-1) and motion(k); features read motion's grey image)
//   partition lane      partition(k)
// so that stage B can start on a frame's tracks (which need the motion inputs only) while its partition and
// features are still being made, and a frame's stage A costs the time of its longest lane, not of their sum. The
// corner tracks of frame k depend on stage A of frame k-1 only (its grey pyramid and corners), so they are made
// here, beside stage B of frame k-1, instead of on stage B's own critical path.
// Stage A owns the ORB extractor (built from the SLAM core's ORB options, whose scale pyramid the core's frames
// use): the core is handed the features with each frame (SlamSystem::track) and extracts nothing itself.
// Declared dependencies on stage B of earlier frames (StageBHandoff), used only by the masked ORB extraction
// (Dynamic.priorMaskedExtraction; see extractFeatures):
//   features(k)  <- the dilated person mask of frame k-1
//                <- whether a map exists after frame k-2
// Frame k-1's mask is known early in its stage B, before its judgement and tracking, so features(k) overlaps
// them; the map state after k-2 is the newest one surely known when frame k is pushed with one frame of
// look-ahead. Each input is named by its frame number and waited for through a future, so the results are the
// same however far ahead stage A runs: determinism follows from the dependencies, not from the timing.
//
// Thread safety: push() may be called from one thread (a feeder of a paced source) while another reads and
// releases slots (the pipeline's stage B): the slot list is guarded by a mutex, and a slot's reference stays
// valid while other slots are added or released. The lanes run in their own threads and touch nothing but the
// copies of the inputs their tasks were given.
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>

#include "amos/core/serial_executor.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/feature/orb_extractor.h"
#include "amos/io/rgbd_frame.h"
#include "amos/segmentation/segmentation_worker.h"
#include "amos/system/frame_slot.h"

namespace amos::system {

// The stage-A tasks that a front-end mode schedules.
struct StageATasks {
  bool segmentation = false;       // the person network, on the frames the schedule names (every frame: auditing)
  bool geometry = false;           // LK pyramid, corners and superpixel partition of the geometric stage
  bool masked_extraction = false;  // ORB detection outside the previous frame's person mask (when it is large)
  static StageATasks forMode(const dynamic::DynamicOptions& options);
};

// The hand-offs of earlier frames that features(k) reads (invalid future: none, e.g. for the first frames).
struct PreparationInputs {
  std::shared_future<cv::Mat> previous_dilated_mask;  // frame k-1's
  std::shared_future<bool> map_ready_two_back;        // after frame k-2
};

// The grey image of the frame's colour image (CV_8UC3 -> CV_8U): what ORB extraction and the LK pyramid read.
cv::Mat toGray(const io::RgbdFrame& frame);

// The tasks of stage A, each a pure function of the frame, the options and its declared inputs.
FrameMotionInput prepareMotion(const io::RgbdFrame& frame, const StageATasks& tasks,
                               const dynamic::DynamicOptions& options);
SlotOrbFeatures extractFeatures(const cv::Mat& gray, const StageATasks& tasks, const dynamic::DynamicOptions& options,
                                const feature::OrbExtractor& extractor, const PreparationInputs& inputs);
FramePartition partitionFrame(const io::RgbdFrame& frame, const dynamic::DynamicOptions& options);
// The corners of `previous` tracked into `current` (both from prepareMotion with the geometric stage on).
FrameCornerTracks trackFrameCorners(const FrameMotionInput& previous, const FrameMotionInput& current,
                                    const dynamic::CornerTrackingOptions& options);

class FrameScheduler {
 public:
  // `orb`: the options the features are extracted with (the SLAM core's, SlamOptions::orb). `segmentation` is
  // required when the mode segments (StageATasks::segmentation) and ignored otherwise.
  FrameScheduler(const feature::OrbOptions& orb, const dynamic::DynamicOptions& options,
                 std::unique_ptr<segmentation::SegmentationWorker> segmentation);
  // Drops the slots still waiting (their hand-offs are broken, so no task waits for them), then stops the lanes.
  ~FrameScheduler();
  FrameScheduler(const FrameScheduler&) = delete;
  FrameScheduler& operator=(const FrameScheduler&) = delete;

  // Frames that may be pushed ahead of stage B: push() refuses more (stage-A tasks wait for the hand-offs of
  // frames that stage B has not reached, so an unbounded run-ahead could only queue up, never help).
  static constexpr std::size_t kMaxAhead = 4;

  // Schedules the frame's stage-A tasks into a new slot and returns its number. `processed`: frames stage B has
  // finished; at most kMaxAhead pushed frames may wait beyond it (core::Error otherwise). The lanes keep
  // references to the frame's images (cv::Mat shares them): do not write into them.
  FrameNumber push(io::RgbdFrame frame, FrameNumber processed);
  // The slot of a pushed frame that has not been released.
  FrameSlot& slot(FrameNumber number);
  // Drops the slots before `first_kept` (stage B no longer needs them).
  void release(FrameNumber first_kept);
  // Frames pushed so far.
  FrameNumber pushed() const;

  // Stops the segmentation lane (frames already queued are still segmented). Idempotent.
  void closeSegmentation();
  const StageATasks& tasks() const { return tasks_; }
  const segmentation::SegmentationWorker* segmentation() const { return segmentation_.get(); }

 private:
  // The frame's segmentation task(s), when the schedule (or the audit) names it.
  void scheduleSegmentation(FrameSlot& slot);

  const feature::OrbExtractor extractor_;  // used by the frame lane only
  dynamic::DynamicOptions options_;
  StageATasks tasks_;
  std::unique_ptr<segmentation::SegmentationWorker> segmentation_;
  mutable std::mutex mutex_;     // guards slots_, next_number_ and published_
  std::deque<FrameSlot> slots_;  // consecutive numbers, the oldest kept first
  FrameNumber next_number_ = 0;  // numbers given out
  FrameNumber published_ = 0;    // slots filled in and visible to slot() and pushed()
  // The hand-offs of the last two frames pushed (oldest first): what preparation of the next frame declares.
  // Touched by push() only.
  std::deque<StageBHandoff> recent_handoffs_;
  // The last scheduled segmentation, whose people the next one masks again when it does not detect. Touched by
  // push() only.
  std::shared_future<segmentation::SegmentationResult> last_segmentation_;
  // The motion input of the last frame pushed, whose corners the next frame's tracks start from. Touched by push()
  // only.
  std::shared_future<FrameMotionInput> last_motion_;
  // Last members: stopped and joined first, before anything their tasks use goes away.
  std::unique_ptr<core::SerialExecutor> frame_lane_;
  std::unique_ptr<core::SerialExecutor> partition_lane_;  // geometric stage only
};

}  // namespace amos::system
