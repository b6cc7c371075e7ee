#include "amos/system/frame_scheduler.h"

#include <opencv2/imgproc.hpp>

#include <string>
#include <utility>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"

namespace amos::system {

StageATasks StageATasks::forMode(const dynamic::DynamicOptions& options) {
  using dynamic::DynamicMode;
  StageATasks t;
  t.segmentation = options.mode == DynamicMode::kPrior || options.mode == DynamicMode::kFull;
  t.geometry = options.mode == DynamicMode::kGeometry || options.mode == DynamicMode::kFull;
  t.masked_extraction = t.segmentation && options.prior_masked_extraction;
  return t;
}

cv::Mat toGray(const io::RgbdFrame& frame) {
  core::require(frame.bgr.type() == CV_8UC3, "toGray: colour image must be CV_8UC3");
  cv::Mat gray;
  cv::cvtColor(frame.bgr, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

FrameMotionInput prepareMotion(const io::RgbdFrame& frame, const StageATasks& tasks,
                               const dynamic::DynamicOptions& options) {
  const double cpu_start = core::threadCpuMs();
  FrameMotionInput motion;
  motion.gray = toGray(frame);
  if (tasks.geometry) {
    core::Stopwatch watch;
    motion.pyramid = dynamic::buildPyramid(motion.gray, options.tracking);
    motion.pyramid_ms = watch.elapsedMs();
    watch.restart();
    motion.corners = dynamic::detectCorners(motion.gray, options.tracking);
    motion.corners_ms = watch.elapsedMs();
  }
  motion.cpu_ms = core::threadCpuMs() - cpu_start;
  return motion;
}

FrameCornerTracks trackFrameCorners(const FrameMotionInput& previous, const FrameMotionInput& current,
                                    const dynamic::CornerTrackingOptions& options) {
  const double cpu_start = core::threadCpuMs();
  core::Stopwatch watch;
  FrameCornerTracks out;
  out.tracks = dynamic::trackPoints({previous.pyramid, current.pyramid}, previous.corners, options);
  out.made = true;
  out.ms = watch.elapsedMs();
  out.cpu_ms = core::threadCpuMs() - cpu_start;
  return out;
}

SlotOrbFeatures extractFeatures(const cv::Mat& gray, const StageATasks& tasks, const dynamic::DynamicOptions& options,
                                const feature::OrbExtractor& extractor, const PreparationInputs& inputs) {
  const double cpu_start = core::threadCpuMs();
  SlotOrbFeatures out;
  // The previous frame's mask rather than this frame's: waiting for this frame's segmentation would put the
  // segmenter and the extractor one after the other on every frame. People move a few pixels between frames, well
  // inside the mask's dilation; keypoints that still land on a person are removed with this frame's mask as always.
  cv::Mat allowed;
  if (tasks.masked_extraction && inputs.previous_dilated_mask.valid()) {
    core::Stopwatch wait;
    const cv::Mat& dynamic = inputs.previous_dilated_mask.get();
    const bool map_ready = inputs.map_ready_two_back.valid() && inputs.map_ready_two_back.get();
    out.handoff_wait_ms = wait.elapsedMs();
    if (!dynamic.empty()) {
      const bool large = cv::countNonZero(dynamic) >=
                         options.prior_masked_extraction_coverage * static_cast<double>(dynamic.total());
      // Before the map exists the frame alone must supply the points to start it: the mask steers at any coverage.
      if (large || !map_ready) allowed = dynamic == 0;
    }
  }
  core::Stopwatch watch;
  out.features.gray = gray;
  extractor.extract(out.features.gray, out.features.keypoints, out.features.descriptors, allowed);
  out.features.extract_ms = watch.elapsedMs();
  out.cpu_ms = core::threadCpuMs() - cpu_start;
  return out;
}

FramePartition partitionFrame(const io::RgbdFrame& frame, const dynamic::DynamicOptions& options) {
  const double cpu_start = core::threadCpuMs();
  FramePartition out;
  out.partition = dynamic::computeGeometricPartition(frame.bgr, frame.depth, options.superpixel, options.cluster);
  // The mask building's frame-only part too, so that stage B does not wait for it.
  out.partition.graph =
      dynamic::superpixelGraph(out.partition.segmentation, frame.depth, options.reprojection.depth_edge_ratio);
  out.cpu_ms = core::threadCpuMs() - cpu_start;
  return out;
}

FrameScheduler::FrameScheduler(const feature::OrbOptions& orb, const dynamic::DynamicOptions& options,
                               std::unique_ptr<segmentation::SegmentationWorker> segmentation)
    : extractor_(orb),
      options_(options),
      tasks_(StageATasks::forMode(options)),
      segmentation_(std::move(segmentation)),
      // Room for every task of every frame that may be ahead (motion, corner tracks, features), so that push()
      // never blocks on a task waiting for stage B.
      frame_lane_(std::make_unique<core::SerialExecutor>(3 * (kMaxAhead + 1))) {
  if (tasks_.geometry) partition_lane_ = std::make_unique<core::SerialExecutor>(kMaxAhead + 1);
  core::require(!tasks_.segmentation || segmentation_ != nullptr,
                "mode " + dynamic::toString(options_.mode) + " needs the person segmenter, but none was created");
}

FrameScheduler::~FrameScheduler() {
  slots_.clear();  // breaks the hand-off promises, so a task that waits for one returns
  recent_handoffs_.clear();
  last_segmentation_ = {};
  partition_lane_.reset();
  frame_lane_.reset();
  closeSegmentation();
}

FrameNumber FrameScheduler::push(io::RgbdFrame frame, FrameNumber processed) {
  FrameSlot* slot = nullptr;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    core::require(next_number_ - processed < kMaxAhead,
                  "FrameScheduler: " + std::to_string(next_number_ - processed) +
                      " frames already wait for stage B; process one before pushing more");
    slot = &slots_.emplace_back();
    slot->number = next_number_++;
  }
  // Filled in without the lock (submitting may wait for room in a lane) and published at the end: slot() and
  // pushed() see only published slots.
  slot->frame = std::move(frame);
  slot->handoff.dilated_prior_mask = slot->dilated_prior_mask.get_future().share();
  slot->handoff.map_ready = slot->map_ready.get_future().share();
  const io::RgbdFrame& f = slot->frame;
  if (tasks_.segmentation) scheduleSegmentation(*slot);
  PreparationInputs inputs;
  if (!recent_handoffs_.empty()) inputs.previous_dilated_mask = recent_handoffs_.back().dilated_prior_mask;
  if (recent_handoffs_.size() == 2) inputs.map_ready_two_back = recent_handoffs_.front().map_ready;
  // Each task holds its own copies of what it reads (cv::Mat headers share the pixels), never the slot.
  slot->motion = frame_lane_->submit([frame = f, tasks = tasks_, this] { return prepareMotion(frame, tasks, options_); })
                     .share();
  slot->corner_tracks = frame_lane_->submit([previous = last_motion_, motion = slot->motion, tasks = tasks_, this] {
    if (!tasks.geometry || !previous.valid()) return FrameCornerTracks{};
    return trackFrameCorners(previous.get(), motion.get(), options_.tracking);
  });
  last_motion_ = slot->motion;
  slot->features = frame_lane_->submit([motion = slot->motion, inputs, tasks = tasks_, this] {
    return extractFeatures(motion.get().gray, tasks, options_, extractor_, inputs);
  });
  if (partition_lane_) slot->partition = partition_lane_->submit([frame = f, this] { return partitionFrame(frame, options_); });
  recent_handoffs_.push_back(slot->handoff);
  if (recent_handoffs_.size() > 2) recent_handoffs_.pop_front();
  std::lock_guard<std::mutex> lock(mutex_);
  published_ = next_number_;
  return slot->number;
}

void FrameScheduler::scheduleSegmentation(FrameSlot& slot) {
  const io::RgbdFrame& f = slot.frame;
  const bool scheduled = options_.prior.isScheduled(slot.number);
  const bool detects = options_.prior.detects(slot.number) || !last_segmentation_.valid();
  if (scheduled) {
    slot.segmentation = detects ? segmentation_->submit(f.index, f.bgr, f.depth).share()
                                : segmentation_->resubmit(f.index, f.bgr, f.depth, last_segmentation_).share();
    last_segmentation_ = slot.segmentation;
  }
  if (options_.prior.audit_predictions)
    slot.audit_segmentation = scheduled && detects ? slot.segmentation : segmentation_->submit(f.index, f.bgr, f.depth).share();
}

FrameNumber FrameScheduler::pushed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return published_;
}

FrameSlot& FrameScheduler::slot(FrameNumber number) {
  std::lock_guard<std::mutex> lock(mutex_);
  core::require(!slots_.empty() && number >= slots_.front().number && number < published_,
                "FrameScheduler: frame " + std::to_string(number) + " was not pushed or was already released");
  return slots_[number - slots_.front().number];
}

void FrameScheduler::release(FrameNumber first_kept) {
  std::lock_guard<std::mutex> lock(mutex_);
  while (!slots_.empty() && slots_.front().number < first_kept) slots_.pop_front();
}

void FrameScheduler::closeSegmentation() {
  if (segmentation_) segmentation_->close();
}

}  // namespace amos::system
