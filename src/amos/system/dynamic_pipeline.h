#pragma once
// The full per-frame pipeline of the paper (Fig. 1): the anti-dynamics front end wrapped around SlamSystem.
//   1. submit the frame to the segmentation worker (prior objects, Sec. III-A), which runs in its own thread ...
//   2. ... while this thread extracts ORB features (SlamSystem::extract);
//   3. initial pose from three models (Sec. III-D): reference-keyframe LK + EPnP, last-frame corners + EPnP,
//      constant velocity; the one with most inliers wins;
//   4. dynamic mask from the two stages (DynamicFrontEnd: superpixel clusters scored by reprojection error,
//      epipolar judgement of prior and geometric candidate regions, Sec. III-B/C);
//   5. tracking with the masked keypoints removed and the initial pose offered to the tracker.
// Mode none skips 1, 3 and 4 (plain ORB-SLAM-style tracking); prior skips 3 and the geometric stage; geometry
// skips 1. Threading: process() is called from one thread; the segmentation worker is the only other thread
// besides local mapping, and frames reach it through a bounded queue (results come back through futures).
//
// Look-ahead: when the caller already holds the next frame it passes it to process(); the next frame is then
// submitted to the segmentation worker before this frame is tracked, so the worker segments frame k+1 while this
// thread runs the whole front end and tracking of frame k (instead of only ORB extraction), and frame k+1's
// masks are usually ready when process(k+1) needs them. Every frame is still segmented on its own, in order, by
// the same segmenter, so the masks (and, in deterministic mode, the trajectory) are the same with or without
// look-ahead; only the waiting changes.
// The look-ahead frame is also prepared ahead in a second worker thread: what depends on nothing but that frame
// (ORB features, its LK pyramid, its superpixels and geometric clusters of Sec. III-B) is computed while this
// thread tracks the current frame, which leaves this thread only the work that needs the last frame or the map
// (corner tracks, initial pose, judgement, tracking). The preparation is the same pure function with or without
// look-ahead, so the results do not change either.
// Masked extraction (Dynamic.priorMaskedExtraction): when people covered at least half of the view, a frame's ORB
// features are detected outside the dilated person mask of the segmentation that served the previous frame, so
// the feature budget goes to the static part of the view (the preparation then waits for that segmentation, which
// started at least a frame earlier). Both paths use the same mask, so this too is the same with or without
// look-ahead.
//
// Segmentation schedule (Dynamic.Prior.*): the network segments every interval-th processed frame, and frame k
// uses the segmentation of frame baseFor(k) (at least `lag` frames old) carried to frame k by the motion of the
// LK tracks inside each person (dynamic::PriorMaskPropagator). The schedule is a function of the frame count
// alone, so runs stay deterministic. interval 1, lag 0 is the paper's every-frame segmentation.
#include <opencv2/core.hpp>

#include <cstdint>
#include <deque>
#include <future>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "amos/core/serial_executor.h"
#include "amos/core/stage_timer.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/dynamic_front_end.h"
#include "amos/dynamic/prior_propagation.h"
#include "amos/segmentation/segmentation_worker.h"
#include "amos/system/slam_system.h"

namespace amos::system {

// What one frame needs that depends on nothing but its own images; computed ahead for the look-ahead frame.
struct PreparedFrame {
  ExtractedFeatures features;
  dynamic::ImagePyramid pyramid;  // LK pyramid of features.gray (empty when the geometric stage is off)
  std::vector<cv::Point2f> corners;  // its corners, tracked into the next frame (geometric stage only)
  // Superpixels and clusters (geometric stage only, and only when prepared ahead: computed inline, the front end
  // makes them itself when it needs them).
  std::optional<dynamic::GeometricPartition> partition;
  double pyramid_ms = 0, corners_ms = 0;
  double segmentation_wait_ms = 0;  // waiting for the previous frame's prior mask before a masked extraction
  double cpu_ms = 0;  // CPU time of the preparing thread
};

// A carried-over person mask against the network's own mask of the same frame (Dynamic.Prior.auditPredictions).
struct PriorAudit {
  double iou = 1;      // undilated carried mask vs the network's mask (two empty masks: 1)
  double covered = 1;  // share of the network's mask inside the dilated carried mask: what removal needs
};

struct DynamicFrameOutput {
  FrameOutput slam;
  cv::Mat dynamic_mask;  // CV_8U, 255 = dynamic (empty in mode none)
  cv::Mat prior_mask;    // undilated segmentation union (empty without segmentation)
  std::optional<dynamic::PoseModel> initial_pose_model;  // which model of III-D won, when one ran
  double removed_fraction = 0;  // keypoints removed by the mask / keypoints extracted
};

class DynamicPipeline {
 public:
  // `segmentation` is required for modes prior and full and ignored (may be null) otherwise.
  DynamicPipeline(SlamSystem& slam, const dynamic::DynamicOptions& options,
                  std::unique_ptr<segmentation::SegmentationWorker> segmentation);
  ~DynamicPipeline();

  // `next`: the frame that the following process() call will get, when the caller already has it (may be null).
  // The pipeline keeps a reference to next's images until that call: do not write into them.
  DynamicFrameOutput process(const io::RgbdFrame& frame, const io::RgbdFrame* next = nullptr);
  // Closes the segmentation worker and finishes the SLAM system.
  void finish();

  dynamic::DynamicMode mode() const { return options_.mode; }
  // Per-stage times of the front end (segmentation wait, initial pose, superpixels, ...), in milliseconds.
  const core::StageTimes& times() const { return times_; }
  // Fraction of the extracted keypoints that the dynamic mask removed, one value per processed frame.
  const std::vector<double>& removedFractions() const { return removed_fractions_; }
  // With Dynamic.Prior.auditPredictions: per frame whose person mask was carried over from an earlier
  // segmentation, how it compares with the network's own mask of the frame (empty otherwise).
  const std::vector<PriorAudit>& priorAudit() const { return prior_audit_; }

 private:
  bool usesSegmentation() const;
  // Submits `frame` (processed frame number `counter`) unless it is already on its way.
  void requestSegmentation(const io::RgbdFrame& frame, std::size_t counter);
  // The segmentation submitted for processed frame `counter` (invalid when there is none).
  std::shared_future<segmentation::SegmentationResult> segmentationOf(std::size_t counter) const;
  // This frame's prior masks (undilated, dilated): the base segmentation carried to this frame by `flow`.
  std::pair<cv::Mat, cv::Mat> priorMasks(std::size_t counter, dynamic::FrameFlow flow);
  bool masksExtraction() const;
  // Everything of `frame` that needs only the frame; with_partition adds the geometric partition. With
  // masksExtraction(), ORB features are detected outside `previous_mask`, the dilated prior mask of the frame
  // processed before this one (a future: the look-ahead preparation waits for it; invalid = no mask) (the
  // frame processed before this one; invalid: no mask).
  // `map_ready`: whether the map existed two frames before `frame` (the newest state a look-ahead preparation can
  // know; the inline path passes the same one, so both give the same features).
  PreparedFrame prepare(const io::RgbdFrame& frame, bool with_partition,
                        std::shared_future<cv::Mat> previous_mask, bool map_ready) const;
  // Hands `frame` to the look-ahead worker unless it is already there.
  void requestPreparation(const io::RgbdFrame& frame,
                          const std::shared_future<cv::Mat>& previous_mask, bool map_ready);
  // The prepared frame from the worker when it was requested, else prepared here.
  PreparedFrame takePreparation(const io::RgbdFrame& frame,
                                const std::shared_future<cv::Mat>& previous_mask,
                                bool map_ready);
  bool usesGeometry() const;
  std::optional<core::SE3> initialPose(const dynamic::ImagePyramid& current,
                                       const std::vector<dynamic::PointTrack>& tracks,
                                       std::optional<dynamic::PoseModel>& model);
  void rememberKeyFramePyramid(const dynamic::ImagePyramid& pyramid);

  struct LastFrame {
    cv::Mat gray, depth;
    cv::Mat dynamic_mask;           // its final dynamic mask (empty in mode none)
    dynamic::ImagePyramid pyramid;  // LK pyramid of gray (empty when the geometric stage is off)
    std::vector<cv::Point2f> corners;  // corners of gray (dynamic::detectCorners), tracked into the next frame
    core::SE3 T_cw = core::SE3::Identity();
  };

  SlamSystem& slam_;
  dynamic::DynamicOptions options_;
  dynamic::DynamicFrontEnd front_end_;
  std::unique_ptr<segmentation::SegmentationWorker> segmentation_;
  // Segmentations submitted to the worker, by processed-frame number, oldest first; dropped once no frame to come
  // uses them. A frame is also known by its image buffer, so a look-ahead frame that the caller announced but did
  // not process is not mistaken for the one that came instead.
  struct Submitted {
    std::size_t counter = 0;
    const void* image = nullptr;
    std::shared_future<segmentation::SegmentationResult> result;  // shared: the look-ahead worker may wait on it too
  };
  std::deque<Submitted> submitted_;
  std::size_t processed_ = 0;  // frames processed so far = the number of the frame being processed
  // The dilated prior mask of the frame processed last, which steers the next frame's ORB extraction.
  std::shared_future<cv::Mat> previous_mask_;
  // Whether the map existed after the frame before the previous one (see prepare()).
  bool map_ready_two_frames_back_ = false;
  // The person masks between segmentations, the frame whose segmentation they started from, and the recent
  // frames' tracks (to carry a segmentation that arrives late up to the current frame).
  std::optional<dynamic::PriorMaskPropagator> propagator_;
  std::size_t propagator_base_ = 0;
  std::deque<std::pair<std::size_t, dynamic::FrameFlow>> flows_;
  std::vector<PriorAudit> prior_audit_;
  // Frames handed to the look-ahead worker (same rules as submitted_).
  struct Preparing {
    std::size_t index = 0;
    const void* image = nullptr;
    std::future<PreparedFrame> result;
  };
  std::deque<Preparing> preparing_;
  std::optional<LastFrame> last_;
  // LK pyramids of recent keyframes by id, for the reference-keyframe LK model (bounded: old ones are dropped).
  std::deque<std::pair<std::uint64_t, dynamic::ImagePyramid>> keyframe_pyramids_;
  core::StageTimes times_;
  std::vector<double> removed_fractions_;
  // The thread that prepares look-ahead frames (created on the first look-ahead frame). Last member: it is stopped
  // and joined first, before anything its jobs use goes away.
  std::unique_ptr<core::SerialExecutor> look_ahead_;
};

}  // namespace amos::system
