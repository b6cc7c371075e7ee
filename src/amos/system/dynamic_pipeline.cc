#include "amos/system/dynamic_pipeline.h"

#include <opencv2/calib3d.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>
#include <utility>

#include "amos/core/serial_executor.h"
#include "amos/core/error.h"
#include "amos/dynamic/initial_pose_models.h"
#include "amos/dynamic/reprojection_scoring.h"
#include "amos/segmentation/segment_masks.h"

namespace amos::system {

namespace {

// Keyframe images kept for the reference-keyframe model: the reference keyframe is nearly always among the most
// recent ones (it is the keyframe sharing most points with the current frame).
constexpr std::size_t kKeyFrameImages = 16;

// Undistorted keyframe keypoints back to raw pixels, where LK on the raw keyframe image needs them.
std::vector<cv::Point2f> distortPixels(const std::vector<cv::Point2f>& undistorted, const core::PinholeCamera& camera) {
  if (!camera.intrinsics().hasDistortion() || undistorted.empty()) return undistorted;
  std::vector<cv::Point3f> rays;
  rays.reserve(undistorted.size());
  for (const auto& p : undistorted) {
    rays.emplace_back(static_cast<float>((p.x - camera.cx()) / camera.fx()),
                      static_cast<float>((p.y - camera.cy()) / camera.fy()), 1.0f);
  }
  std::vector<cv::Point2f> raw;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera.K(), camera.distortion(), raw);
  return raw;
}

// The per-stage CPU costs ("cpu.*" stages) use core::threadCpuMs: OpenCV runs single-threaded here
// (Segmentation.threads), so a stage's OpenCV work is in its thread's time.
using core::threadCpuMs;

PriorAudit auditPrediction(const cv::Mat& carried, const cv::Mat& carried_dilated,
                           const segmentation::SegmentationResult& computed) {
  PriorAudit a;
  a.iou = segmentation::maskIoU(carried, computed.mask);
  const int truth = cv::countNonZero(computed.mask);
  a.covered = truth == 0 ? 1.0 : cv::countNonZero(computed.mask & carried_dilated) / static_cast<double>(truth);
  return a;
}

}  // namespace

DynamicPipeline::DynamicPipeline(SlamSystem& slam, const dynamic::DynamicOptions& options,
                                 std::unique_ptr<segmentation::SegmentationWorker> segmentation)
    : slam_(slam),
      options_(options),
      front_end_(slam.sensor()->camera(), options),
      segmentation_(std::move(segmentation)) {
  options_.check();
  core::require(!usesSegmentation() || segmentation_ != nullptr,
                "mode " + dynamic::toString(options_.mode) + " needs the person segmenter, but none was created");
}

DynamicPipeline::~DynamicPipeline() {
  look_ahead_.reset();
  if (segmentation_) segmentation_->close();
}

bool DynamicPipeline::usesSegmentation() const {
  return options_.mode == dynamic::DynamicMode::kPrior || options_.mode == dynamic::DynamicMode::kFull;
}

bool DynamicPipeline::usesGeometry() const {
  return options_.mode == dynamic::DynamicMode::kGeometry || options_.mode == dynamic::DynamicMode::kFull;
}

void DynamicPipeline::rememberKeyFramePyramid(const dynamic::ImagePyramid& pyramid) {
  keyframe_pyramids_.emplace_back(slam_.tracker().referenceKeyFrameView().id, pyramid);
  if (keyframe_pyramids_.size() > kKeyFrameImages) keyframe_pyramids_.pop_front();
}

std::optional<core::SE3> DynamicPipeline::initialPose(const dynamic::ImagePyramid& current,
                                                      const std::vector<dynamic::PointTrack>& tracks,
                                                      std::optional<dynamic::PoseModel>& model) {
  const core::PinholeCamera& camera = slam_.sensor()->camera();
  // Model 1: the reference keyframe's keypoints that carry map points, tracked by LK into this frame.
  dynamic::PoseCorrespondences from_keyframe;
  const tracking::ReferenceKeyFrameView view = slam_.tracker().referenceKeyFrameView();
  for (const auto& [id, keyframe] : keyframe_pyramids_) {
    if (id != view.id) continue;
    std::vector<std::size_t> with_point;
    for (std::size_t i = 0; i < view.keypoints.size(); ++i)
      if (view.has_point[i]) with_point.push_back(i);
    std::vector<cv::Point2f> pixels;
    std::vector<Eigen::Vector3d> points_w;
    for (const std::size_t i : dynamic::everyKth(with_point, options_.initial_pose.keyframe_max_points)) {
      pixels.push_back(view.keypoints[i].pt);
      points_w.push_back(view.points_w[i]);
    }
    dynamic::CornerTrackingOptions tracking = options_.tracking;
    tracking.forward_backward_check = options_.initial_pose.keyframe_forward_backward;
    from_keyframe = dynamic::keyframeCorrespondences({keyframe, current}, distortPixels(pixels, camera), points_w,
                                                     camera, tracking);
    break;
  }
  // Model 2: last-frame corners lifted with the last depth and pose (Eq. 6).
  const auto lifted = dynamic::backProjectTracks(tracks, last_->depth, last_->T_cw, camera, options_.reprojection);
  const dynamic::PoseCorrespondences from_last = dynamic::lastFrameCorrespondences(tracks, lifted, camera);
  // Model 3: constant velocity.
  const dynamic::InitialPoseResult result = dynamic::estimateInitialPose(
      from_keyframe, from_last, last_->T_cw, slam_.tracker().velocity(), camera, options_.initial_pose);
  if (!result.ok) return std::nullopt;
  model = result.model;
  return result.T_cw;
}

void DynamicPipeline::requestSegmentation(const io::RgbdFrame& frame, std::size_t counter) {
  for (auto it = submitted_.begin(); it != submitted_.end(); ++it) {
    if (it->counter != counter) continue;
    if (it->image == frame.bgr.data) return;
    submitted_.erase(it);  // announced as the next frame, but another one came (its result is never used)
    break;
  }
  Submitted s{counter, frame.bgr.data, segmentation_->submit(frame.index, frame.bgr, frame.depth)};
  const auto at = std::find_if(submitted_.begin(), submitted_.end(),
                               [&](const Submitted& other) { return other.counter > counter; });
  submitted_.insert(at, std::move(s));
}

std::shared_future<segmentation::SegmentationResult> DynamicPipeline::segmentationOf(std::size_t counter) const {
  for (const Submitted& s : submitted_)
    if (s.counter == counter) return s.result;
  return {};
}

std::pair<cv::Mat, cv::Mat> DynamicPipeline::priorMasks(std::size_t counter, dynamic::FrameFlow flow) {
  const std::size_t base = options_.prior.baseFor(counter);
  std::shared_future<segmentation::SegmentationResult> pending = segmentationOf(base);
  core::require(pending.valid(), "DynamicPipeline: the segmentation of frame " + std::to_string(base) +
                                     " that frame " + std::to_string(counter) + " needs was never requested");
  const bool fresh = !propagator_ || propagator_base_ != base;
  if (fresh) {
    core::Stopwatch wait;
    const segmentation::SegmentationResult& segmented = pending.get();
    times_.add("dynamic.segmentation_wait", wait.elapsedMs());
    times_.add("dynamic.segmentation", segmented.segment_ms);
    times_.add("cpu.segmentation", segmented.segment_cpu_ms);
    if (!propagator_) propagator_.emplace(segmented.mask.size(), segmentation_->dilation(), options_.prior);
    propagator_->reset(segmented.instances);
    propagator_base_ = base;
    for (const auto& [c, old_flow] : flows_)  // a segmentation `lag` frames old: carried over the frames since
      if (c > base && c < counter) propagator_->step(old_flow);
  }
  if (counter > base) propagator_->step(flow);
  flows_.emplace_back(counter, std::move(flow));
  const std::size_t keep = static_cast<std::size_t>(options_.prior.interval + options_.prior.lag);
  while (flows_.size() > keep) flows_.pop_front();
  if (counter == base) {  // this frame's own segmentation: exactly what the network gave (the paper's way)
    const segmentation::SegmentationResult& segmented = pending.get();
    return {segmented.mask, segmented.dilated_mask};
  }
  return {propagator_->mask(), propagator_->dilatedMask()};
}

bool DynamicPipeline::masksExtraction() const {
  return usesSegmentation() && options_.prior_masked_extraction && !options_.judge_prior_regions;
}

PreparedFrame DynamicPipeline::prepare(const io::RgbdFrame& frame, bool with_partition,
                                      std::shared_future<cv::Mat> previous_mask,
                                      bool map_ready) const {
  const double cpu_start = threadCpuMs();
  PreparedFrame prepared;
  core::Stopwatch convert;
  const cv::Mat gray = SlamSystem::toGray(frame);
  const double convert_ms = convert.elapsedMs();
  // What does not need the segmentation first, so that a wait for it comes as late as possible.
  if (usesGeometry()) {
    core::Stopwatch watch;
    prepared.pyramid = dynamic::buildPyramid(gray, options_.tracking);
    prepared.pyramid_ms = watch.elapsedMs();
    watch.restart();
    prepared.corners = dynamic::detectCorners(gray, options_.tracking);
    prepared.corners_ms = watch.elapsedMs();
    if (with_partition)
      prepared.partition =
          dynamic::computeGeometricPartition(frame.bgr, frame.depth, options_.superpixel, options_.cluster);
  }
  // The previous frame's mask rather than this frame's: waiting for this frame's segmentation would put the
  // segmenter and the extractor one after the other on every frame. People move a few pixels between frames, well
  // inside the mask's dilation; keypoints that still land on a person are removed with this frame's mask as always.
  cv::Mat allowed;
  if (masksExtraction() && previous_mask.valid()) {
    core::Stopwatch wait;
    const cv::Mat& dynamic = previous_mask.get();
    prepared.segmentation_wait_ms = wait.elapsedMs();
    if (!dynamic.empty()) {
      const bool large = cv::countNonZero(dynamic) >=
                         options_.prior_masked_extraction_coverage * static_cast<double>(dynamic.total());
      if (large || !map_ready) allowed = dynamic == 0;
    }
  }
  prepared.features = slam_.extractGray(gray, allowed);
  prepared.features.extract_ms += convert_ms;
  prepared.cpu_ms = threadCpuMs() - cpu_start;
  return prepared;
}

void DynamicPipeline::requestPreparation(const io::RgbdFrame& frame,
                                         const std::shared_future<cv::Mat>& previous_mask,
                                         bool map_ready) {
  for (const Preparing& p : preparing_)
    if (p.index == frame.index && p.image == frame.bgr.data) return;
  // The current and the next frame are the most in flight; room for a few announced-but-skipped ones.
  if (!look_ahead_) look_ahead_ = std::make_unique<core::SerialExecutor>(4);
  // The job holds its own references to the images (cv::Mat headers share the pixels), not to the caller's frame.
  // The partition is made even though whether the frame will have a last frame (and use it) is not known yet.
  preparing_.push_back({frame.index, frame.bgr.data,
                        look_ahead_->submit([this, frame, previous_mask, map_ready] {
                          return prepare(frame, usesGeometry(), previous_mask, map_ready);
                        })});
}

PreparedFrame DynamicPipeline::takePreparation(const io::RgbdFrame& frame,
                                              const std::shared_future<cv::Mat>& previous_mask,
                                              bool map_ready) {
  while (!preparing_.empty() && (preparing_.front().index != frame.index || preparing_.front().image != frame.bgr.data))
    preparing_.pop_front();  // announced but never processed: dropped (the worker still finishes it)
  if (preparing_.empty()) return prepare(frame, false, previous_mask, map_ready);
  core::Stopwatch wait;
  PreparedFrame prepared = preparing_.front().result.get();
  preparing_.pop_front();
  times_.add("dynamic.prepare_wait", wait.elapsedMs());
  return prepared;
}

DynamicFrameOutput DynamicPipeline::process(const io::RgbdFrame& frame, const io::RgbdFrame* next) {
  DynamicFrameOutput out;
  // 1. The segmentations that this and the next frame schedule run in their own thread (this frame's started
  //    during the previous call when that call was given this frame as look-ahead) ...
  const std::size_t counter = processed_++;
  // This frame's dilated prior mask, for the next frame's ORB extraction: promised now, set once it is known.
  std::promise<cv::Mat> mask_for_next;
  std::shared_future<cv::Mat> this_mask = mask_for_next.get_future().share();
  if (usesSegmentation()) {
    const bool audit = options_.prior.audit_predictions;
    if (audit || options_.prior.isScheduled(counter)) requestSegmentation(frame, counter);
    if (next != nullptr && (audit || options_.prior.isScheduled(counter + 1))) requestSegmentation(*next, counter + 1);
  } else {
    mask_for_next.set_value(cv::Mat());
  }
  // 2. ... while this thread extracts features (or takes them from the look-ahead worker, which then goes on with
  //    the next frame).
  // The map's state after the previous frame: what the look-ahead preparation of the next frame can know.
  const bool map_ready_one_frame_back = slam_.tracker().state() != tracking::TrackingState::kNotInitialized;
  PreparedFrame prepared = takePreparation(frame, previous_mask_, map_ready_two_frames_back_);
  if (next != nullptr) requestPreparation(*next, this_mask, map_ready_one_frame_back);
  previous_mask_ = this_mask;
  map_ready_two_frames_back_ = map_ready_one_frame_back;
  const ExtractedFeatures& features = prepared.features;
  dynamic::ImagePyramid& current_pyramid = prepared.pyramid;
  times_.add("cpu.prepare", prepared.cpu_ms);
  if (masksExtraction()) times_.add("dynamic.extraction_segmentation_wait", prepared.segmentation_wait_ms);
  if (!current_pyramid.empty()) {
    times_.add("dynamic.pyramid", prepared.pyramid_ms);
    times_.add("dynamic.corner_detection", prepared.corners_ms);
  }

  FrameExtras extras;
  if (options_.mode != dynamic::DynamicMode::kNone) {
    dynamic::DynamicFrameInput input;
    input.gray = features.gray;
    input.bgr = frame.bgr;
    input.depth = frame.depth;
    if (prepared.partition) input.partition = &*prepared.partition;
    std::vector<dynamic::PointTrack> tracks;
    if (last_) {
      input.last_gray = last_->gray;
      input.last_depth = last_->depth;
      input.T_cw_last = last_->T_cw;
      input.last_mask = last_->dynamic_mask;
      input.T_cw_initial = last_->T_cw;
      if (usesGeometry()) {
        core::Stopwatch watch;
        double cpu = threadCpuMs();
        tracks = dynamic::trackPoints({last_->pyramid, current_pyramid}, last_->corners, options_.tracking);
        times_.add("dynamic.corner_tracking", watch.elapsedMs());
        times_.add("cpu.corner_tracking", threadCpuMs() - cpu);
        watch.restart();
        cpu = threadCpuMs();
        std::optional<dynamic::PoseModel> model;
        extras.initial_T_cw = initialPose(current_pyramid, tracks, model);
        out.initial_pose_model = model;
        times_.add("dynamic.initial_pose", watch.elapsedMs());
        times_.add("cpu.initial_pose", threadCpuMs() - cpu);
        if (extras.initial_T_cw) input.T_cw_initial = *extras.initial_T_cw;
        input.tracks = &tracks;
      }
    }
    if (usesSegmentation()) {
      // 3a. Person masks: this frame's segmentation, or an earlier one carried here by the tracks.
      auto [mask, dilated] = priorMasks(counter, dynamic::FrameFlow{tracks});
      if (options_.prior.audit_predictions && options_.prior.baseFor(counter) != counter)
        prior_audit_.push_back(auditPrediction(mask, dilated, segmentationOf(counter).get()));
      mask_for_next.set_value(dilated);
      input.prior_mask = std::move(dilated);
      out.prior_mask = std::move(mask);
    }
    core::Stopwatch watch;
    const double cpu = threadCpuMs();
    const dynamic::DynamicFrameOutput judged = front_end_.process(input);
    times_.add("dynamic.front_end", watch.elapsedMs());
    times_.add("cpu.front_end", threadCpuMs() - cpu);
    for (const auto& [stage, ms] : judged.timings_ms) times_.add("dynamic." + stage, ms);
    extras.dynamic_mask = judged.mask;
    out.dynamic_mask = judged.mask;
  }

  // 5. Tracking without the dynamic keypoints.
  const double track_cpu = threadCpuMs();
  out.slam = slam_.track(frame, features, extras);
  times_.add("cpu.track", threadCpuMs() - track_cpu);
  const int extracted = out.slam.keypoints + out.slam.removed_dynamic;
  if (extracted > 0) out.removed_fraction = static_cast<double>(out.slam.removed_dynamic) / extracted;
  removed_fractions_.push_back(out.removed_fraction);

  // Segmentations that no frame to come needs any more.
  const std::size_t oldest_needed = options_.prior.baseFor(counter);
  while (!submitted_.empty() && submitted_.front().counter < oldest_needed) submitted_.pop_front();

  const tracking::TrackResult& track = out.slam.track;
  if (track.state == tracking::TrackingState::kOk) {
    last_ = LastFrame{features.gray, frame.depth, out.dynamic_mask, current_pyramid, std::move(prepared.corners),
                      track.T_cw};
    if (usesGeometry() && (track.new_keyframe || track.initialized_map)) rememberKeyFramePyramid(current_pyramid);
  } else {
    last_.reset();  // a lost frame's pose would poison the reprojection test of the next one
  }
  return out;
}

void DynamicPipeline::finish() {
  if (!prior_audit_.empty()) {
    std::vector<double> iou, covered;
    for (const PriorAudit& a : prior_audit_) {
      iou.push_back(a.iou);
      covered.push_back(a.covered);
    }
    spdlog::info("carried-over person masks against the network's own on {} frames: IoU median {:.3f}, 5th "
                 "percentile {:.3f}; share of the network's mask inside the dilated carried mask: median {:.3f}, 5th "
                 "percentile {:.3f}",
                 iou.size(), core::percentile(iou, 0.5), core::percentile(iou, 0.05), core::percentile(covered, 0.5),
                 core::percentile(covered, 0.05));
  }
  if (segmentation_) segmentation_->close();
  slam_.finish();
}

}  // namespace amos::system
