#pragma once
// The full per-frame pipeline of the paper (Fig. 1): the anti-dynamics front end wrapped around SlamSystem, in
// two explicit stages.
//
// The seam with the SLAM core runs one way. Stage A extracts the ORB features (the core extracts nothing), and
// stage B hands the core each frame once, through its one entry point (SlamSystem::track: the features, the dynamic
// mask, the initial pose); it reads nothing of the core but what that call returns, the pose and a TrackingView
// (state, velocity, reference keyframe) as values, which it keeps for the next frame. So the front end depends on
// what the core chose to show, not on the tracker's internals, and the core can be driven and tested alone.
//
// Stage A, push(frame): the pure per-frame work, scheduled ahead into the frame's slot by the FrameScheduler
// (frame_scheduler.h: which tasks a mode schedules, and the dependencies they declare on earlier frames):
// person segmentation (Sec. III-A) in its own lane; grey image, ORB features, LK pyramid, corners and superpixel
// partition (Sec. III-B) in the preparation lane.
//
// Stage B, processNext(): the sequential, stateful work, in frame order, on the oldest pushed frame. The steps, in
// the order they run (each a private member below):
//   1. takeMotion          wait for the slot's motion input (grey image, LK pyramid, corners)
//   2. takeCornerTracks    LK tracks of the last frame's corners into this one, made in   (geometry)
//                          stage A beside stage B of the last frame (frame_scheduler.h)
//   3. personMasks         this frame's segmentation, or an earlier one carried here by    (prior)
//                          the corner tracks
//                          -> hand-off: the dilated mask, for stage A of the next frame (made before the
//                          initial pose, which does not need it, so that the next frame's extraction waits less)
//   4. initialPose         three models (Sec. III-D): reference-keyframe LK + EPnP,       (geometry)
//                          last-frame corners + EPnP, constant velocity (the reference keyframe and the
//                          velocity from the last frame's TrackingView); most inliers wins; after a lost
//                          frame the keyframe model alone (the tracker's recovery searches around its pose)
//   5. judge               the dynamic mask (DynamicFrontEnd, Sec. III-B/C), once the     (not in none)
//                          slot's superpixel partition is there
//   6. track               SlamSystem::track, once the slot's ORB features are there: the features, the dynamic
//                          mask and the initial pose in; the pose and the TrackingView out
//                          -> hand-off: whether a map exists, for stage A two frames on
//   7. remember            what the next frame needs from this one, the TrackingView too (StageBState)
// A mode is the set of stage-A tasks scheduled and the stage-B steps that run: none = 1, 6, 7; prior adds 3 and 5;
// geometry adds 2, 4, 5; full all.
//
// Determinism: stage A reads nothing of stage B but the declared hand-offs, each named by its frame number and
// waited for through a future, and stage B runs in frame order in one thread; so in deterministic mode the
// trajectory is the same whatever the look-ahead. The person-segmentation schedule (Dynamic.Prior.*: every
// interval-th frame segmented, by the detector on every detectEvery-th of those and else by the mask network on the
// last detection's people, used lag frames later, carried in between by PersonMaskCarrier) is a function of the
// frame numbers alone. interval 1, lag 0, detectEvery 1 is the paper's every-frame segmentation.
//
// Threading: processNext() and the other members are called from one thread; push() may be called from that thread
// or from one other (a feeder that hands over frames as a paced source delivers them). Besides them run the two
// stage-A lanes and local mapping (SlamSystem).
//
//   DynamicPipeline pipeline(slam, options, segmentation);
//   pipeline.push(frame0);
//   while (pipeline.waiting() > 0) {
//     if (auto next = source.next()) pipeline.push(*next);  // one frame of look-ahead: A(k+1) runs beside B(k)
//     ProcessedFrame out = pipeline.processNext();      // frame k
//   }
//   pipeline.finish();
#include <opencv2/core.hpp>

#include <atomic>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "amos/core/stage_timer.h"
#include "amos/dynamic/baseline_history.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/dynamic_front_end.h"
#include "amos/segmentation/segmentation_worker.h"
#include "amos/system/frame_scheduler.h"
#include "amos/system/frame_slot.h"
#include "amos/system/person_mask_carrier.h"
#include "amos/system/slam_system.h"

namespace amos::system {

// A carried-over person mask against the network's own mask of the same frame (Dynamic.Prior.auditPredictions).
struct PriorAudit {
  double iou = 1;      // undilated carried mask vs the network's mask (two empty masks: 1)
  double covered = 1;  // share of the network's mask inside the dilated carried mask: what removal needs
};

struct ProcessedFrame {
  io::RgbdFrame frame;  // the frame processed
  FrameOutput slam;
  cv::Mat dynamic_mask;  // CV_8U, 255 = dynamic (empty in mode none)
  cv::Mat prior_mask;    // undilated person mask (empty without segmentation)
  std::optional<dynamic::PoseModel> initial_pose_model;  // which model of III-D won, when one ran
  double removed_fraction = 0;  // keypoints removed by the mask / keypoints extracted
  // The extracted keypoints (image pixels, as detected), before the mask removed any: for observers that mark
  // kept and removed ones (run/run_observer.h). A copy of ~1000 points, microseconds.
  std::vector<cv::Point2f> keypoints;
};

class DynamicPipeline {
 public:
  // `segmentation` is required for modes prior and full and ignored (may be null) otherwise.
  DynamicPipeline(SlamSystem& slam, const dynamic::DynamicOptions& options,
                  std::unique_ptr<segmentation::SegmentationWorker> segmentation);
  ~DynamicPipeline();

  // Stage A: schedules the frame's per-frame work. At most FrameScheduler::kMaxAhead frames may wait.
  // `caller_mask` (CV_8U of the frame's size, non-zero = dynamic; empty = none): what the caller's own detector found
  // (the library API's prior mask). Stage B merges it with the person network's mask into the front end's prior
  // regions (modes prior and full) and into the final dynamic mask (every mode), so its keypoints are left out.
  FrameNumber push(io::RgbdFrame frame, cv::Mat caller_mask = {});
  // Frames pushed and not processed yet.
  std::size_t waiting() const { return scheduler_.pushed() - processed_.load(); }
  // Stage B: processes the oldest waiting frame (core::Error when none waits).
  ProcessedFrame processNext();
  // push() then processNext(): one frame without look-ahead.
  ProcessedFrame process(io::RgbdFrame frame);
  // Closes the segmentation lane and finishes the SLAM system. Frames still waiting are not processed.
  void finish();

  // Whether stage B waits for a person segmentation that is late (default, and what --deterministic needs). A live
  // source (a camera, --realtime) sets false: a frame's pose must not wait for the network while the masks can
  // be carried on by the tracks (PersonMaskCarrier::carryOn); the masks are then at most one period older.
  void setWaitForSegmentation(bool wait) { wait_for_segmentation_ = wait; }
  // Frames whose masks were carried on because the segmentation they were scheduled to start from was late.
  std::size_t segmentationLateFrames() const { return segmentation_late_frames_; }

  dynamic::DynamicMode mode() const { return options_.mode; }
  // Per-stage times of the front end (segmentation wait, initial pose, superpixels, ...), in milliseconds.
  const core::StageTimes& times() const { return times_; }
  // Fraction of the extracted keypoints that the dynamic mask removed, one value per processed frame.
  const std::vector<double>& removedFractions() const { return removed_fractions_; }
  // With Dynamic.Prior.auditPredictions: per frame whose person mask was not a detection of its own (carried over
  // from an earlier segmentation, or masked on an earlier detection's boxes), how it compares with the detector +
  // mask network's result on the frame (empty otherwise).
  const std::vector<PriorAudit>& priorAudit() const { return prior_audit_; }

 private:
  struct LastFrame {
    cv::Mat gray, depth;
    cv::Mat dynamic_mask;           // its final dynamic mask (empty in mode none)
    dynamic::ImagePyramid pyramid;  // LK pyramid of gray (empty when the geometric stage is off)
    std::vector<cv::Point2f> corners;  // corners of gray (dynamic::detectCorners), tracked into the next frame
    core::SE3 T_cw = core::SE3::Identity();
  };
  // What stage B keeps from the past.
  struct StageBState {
    FrameNumber processed = 0;      // frames processed = the number of the next one
    std::optional<LastFrame> last;  // the last frame, when it was tracked
    // LK pyramids of recent keyframes by id, for the reference-keyframe model (bounded: old ones are dropped).
    std::deque<std::pair<std::uint64_t, dynamic::ImagePyramid>> keyframe_pyramids;
    std::optional<PersonMaskCarrier> person_masks;  // modes prior and full
    // Depth and pose of the last tracked frames, the depth evidence's baseline (emptied when a frame is lost, like
    // `last`).
    dynamic::BaselineHistory baseline_history;  // the frames the longer comparisons need
    // The core's tracking state after the last frame (SlamSystem::track's view; before the first frame: not
    // initialised, no reference keyframe), which the initial-pose models of the next frame start from.
    TrackingView tracking_view;
  };

  // The steps of stage B (see the header comment), in order.
  FrameMotionInput takeMotion(FrameSlot& slot);
  FrameCornerTracks takeCornerTracks(FrameSlot& slot);
  std::optional<core::SE3> initialPose(const dynamic::ImagePyramid& current,
                                       const std::vector<dynamic::PointTrack>& tracks,
                                       std::optional<dynamic::PoseModel>& model);
  PersonMaskCarrier::Masks personMasks(FrameSlot& slot, const std::vector<dynamic::PointTrack>& tracks);
  // The dynamic mask (CV_8U, 255 = dynamic).
  cv::Mat judge(dynamic::FrontEndInput input);
  void track(const TrackInput& input, ProcessedFrame& out);
  void remember(const ProcessedFrame& out, FrameMotionInput motion);
  // The caller's mask of frame `number` (empty when none was given), taken out of caller_masks_.
  cv::Mat takeCallerMask(FrameNumber number);

  // The slots that stage B will still read from (the segmentation that serves the next frame, and on).
  FrameNumber firstSlotNeeded() const;

  SlamSystem& slam_;
  dynamic::DynamicOptions options_;
  dynamic::DynamicFrontEnd front_end_;
  StageBState state_;
  core::StageTimes times_;
  std::vector<double> removed_fractions_;
  std::vector<PriorAudit> prior_audit_;
  bool wait_for_segmentation_ = true;
  std::size_t segmentation_late_frames_ = 0;
  std::atomic<FrameNumber> processed_{0};
  // The caller masks of pushed frames by frame number (push() may run in another thread than stage B).
  std::mutex caller_masks_mutex_;
  std::map<FrameNumber, cv::Mat> caller_masks_;  // state_.processed, for push() and waiting() from another thread
  // Last member: its lanes are stopped first, before anything their tasks use goes away.
  FrameScheduler scheduler_;
};

}  // namespace amos::system
