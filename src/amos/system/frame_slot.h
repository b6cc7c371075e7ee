#pragma once
// One frame on its way through the two stages of the pipeline (dynamic_pipeline.h):
//   stage A, the pure per-frame work, fills the slot's futures ahead of time (frame_scheduler.h);
//   stage B, the sequential work in frame order, takes them and hands back what stage A of later frames declared
//   it needs (StageBHandoff).
// A slot is keyed by its frame number: the position of the frame in push order, counted from 0. Every frame
// pushed is processed, in that order, so the number names a frame for good and nothing else is needed to find it.
#include <opencv2/core.hpp>

#include <cstddef>
#include <future>
#include <optional>
#include <vector>

#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/geometric_clustering.h"
#include "amos/io/rgbd_frame.h"
#include "amos/segmentation/segmentation_worker.h"
#include "amos/system/slam_system.h"

namespace amos::system {

using FrameNumber = std::size_t;

// Stage A's products for one frame, each made by its own task (frame_scheduler.h says which lane runs which):
// everything that depends on nothing but the frame itself (and the declared hand-offs of earlier frames).
struct FrameMotionInput {
  cv::Mat gray;                      // the grey image (every mode)
  dynamic::ImagePyramid pyramid;     // LK pyramid of gray (geometric stage only)
  std::vector<cv::Point2f> corners;  // its corners, tracked into the next frame (geometric stage only)
  double pyramid_ms = 0, corners_ms = 0;
  double cpu_ms = 0;  // CPU time of the task
};
// The corners of the frame pushed before this one, tracked by LK into this one (geometric stage only): a pure
// function of the two frames' motion inputs, so stage A makes it; stage B uses it when the frame before was tracked
// (its LastFrame holds the same corners and pyramid).
struct FrameCornerTracks {
  std::vector<dynamic::PointTrack> tracks;
  bool made = false;  // false: no frame before this one, or the geometric stage is off
  double ms = 0, cpu_ms = 0;
};

struct SlotOrbFeatures {
  ExtractedFeatures features;  // ORB keypoints and descriptors of the grey image
  double handoff_wait_ms = 0;  // waiting for the hand-offs of earlier frames (masked extraction only)
  double cpu_ms = 0;
};
struct FramePartition {
  dynamic::GeometricPartition partition;  // superpixels and clusters (Sec. III-B)
  double cpu_ms = 0;
};

// What stage B of frame k publishes for stage A of later frames. Futures, so that a stage-A task that needs one
// waits for exactly that frame's value, whatever the timing: the results do not depend on how far ahead stage A
// runs.
struct StageBHandoff {
  // The dilated person mask that served frame k (empty without segmentation); set as soon as it is known, before
  // frame k's judgement and tracking.
  std::shared_future<cv::Mat> dilated_prior_mask;
  // Whether a map exists after frame k was tracked.
  std::shared_future<bool> map_ready;
};

struct FrameSlot {
  FrameNumber number = 0;
  io::RgbdFrame frame;
  // Stage A (valid when the mode schedules the task): the networks' segmentation of this frame, the motion
  // input (always), the ORB features (always) and the superpixel partition.
  std::shared_future<segmentation::SegmentationResult> segmentation;
  // With Dynamic.Prior.auditPredictions, every frame's detector + mask network result, to score what served it.
  std::shared_future<segmentation::SegmentationResult> audit_segmentation;
  std::shared_future<FrameMotionInput> motion;
  std::future<FrameCornerTracks> corner_tracks;
  std::future<SlotOrbFeatures> features;
  std::future<FramePartition> partition;
  // Stage B's hand-offs: set by stage B of this frame, read through `handoff` by stage A of later frames.
  std::promise<cv::Mat> dilated_prior_mask;
  std::promise<bool> map_ready;
  StageBHandoff handoff;
};

}  // namespace amos::system
