#include "amos/system/dynamic_pipeline.h"

#include <chrono>
#include <future>

#include <opencv2/calib3d.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>
#include <utility>

#include "amos/core/error.h"
#include "amos/dynamic/depth_slic.h"
#include "amos/dynamic/initial_pose_models.h"
#include "amos/dynamic/reprojection_scoring.h"
#include "amos/evidence/evidence_sources.h"
#include "amos/segmentation/segment_masks.h"

namespace amos::system {

namespace {

// Keyframe images kept for the reference-keyframe model: the reference keyframe is nearly always among the most
// recent ones (it is the keyframe sharing most points with the current frame).
constexpr std::size_t kKeyFrameImages = 16;

// The per-stage CPU costs ("cpu.*" stages) use core::threadCpuMs: OpenCV runs single-threaded here
// (Segmentation.threads), so a stage's OpenCV work is in its thread's time.
using core::threadCpuMs;

PriorAudit auditPrediction(const PersonMaskCarrier::Masks& carried, const segmentation::SegmentationResult& computed) {
  PriorAudit a;
  a.iou = segmentation::maskIoU(carried.mask, computed.mask);
  const int truth = cv::countNonZero(computed.mask);
  a.covered = truth == 0 ? 1.0 : cv::countNonZero(computed.mask & carried.dilated) / static_cast<double>(truth);
  return a;
}

// 255 where either mask is non-zero (CV_8U); `a` may be empty.
cv::Mat mergedMask(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat merged;
  cv::compare(b, 0, merged, cv::CMP_NE);
  if (!a.empty()) cv::bitwise_or(merged, a, merged);
  return merged;
}

}  // namespace

DynamicPipeline::DynamicPipeline(SlamSystem& slam, const dynamic::DynamicOptions& options,
                                 std::unique_ptr<segmentation::SegmentationWorker> segmentation)
    : slam_(slam),
      options_(options),
      front_end_(slam.sensor()->camera(), options, evidence::makeEvidenceSources(slam.sensor()->camera(), options)),
      scheduler_(slam.options().orb, options, std::move(segmentation)) {
  options_.check();
  if (scheduler_.tasks().geometry) dynamic::prepareDepthSlic();  // before the first frame, not in it
  if (scheduler_.tasks().segmentation)
    state_.person_masks.emplace(scheduler_.segmentation()->dilation(), options_.prior);
  if (options_.depth.enabled || options_.baseline_tracks.enabled)
    state_.baseline_history = dynamic::BaselineHistory(options_.depth.baseline_frames);
}

DynamicPipeline::~DynamicPipeline() = default;

FrameNumber DynamicPipeline::push(io::RgbdFrame frame, cv::Mat caller_mask) {
  if (!caller_mask.empty()) {
    // Pushes come from one thread, so the frame's number is the count pushed so far; stored before the push, so
    // stage B finds it however soon it takes the frame.
    std::lock_guard lock(caller_masks_mutex_);
    caller_masks_[scheduler_.pushed()] = std::move(caller_mask);
  }
  return scheduler_.push(std::move(frame), processed_.load());
}

cv::Mat DynamicPipeline::takeCallerMask(FrameNumber number) {
  std::lock_guard lock(caller_masks_mutex_);
  const auto it = caller_masks_.find(number);
  if (it == caller_masks_.end()) return {};
  cv::Mat mask = std::move(it->second);
  caller_masks_.erase(it);
  return mask;
}

ProcessedFrame DynamicPipeline::process(io::RgbdFrame frame) {
  push(std::move(frame));
  return processNext();
}

FrameMotionInput DynamicPipeline::takeMotion(FrameSlot& slot) {
  core::Stopwatch wait;
  FrameMotionInput motion = slot.motion.get();
  times_.add("dynamic.prepare_wait", wait.elapsedMs());
  if (!motion.pyramid.empty()) {
    times_.add("dynamic.pyramid", motion.pyramid_ms);
    times_.add("dynamic.corner_detection", motion.corners_ms);
  }
  return motion;
}

FrameCornerTracks DynamicPipeline::takeCornerTracks(FrameSlot& slot) {
  core::Stopwatch wait;
  FrameCornerTracks made = slot.corner_tracks.get();
  times_.add("dynamic.corner_tracking_wait", wait.elapsedMs());
  if (made.made) {
    times_.add("dynamic.corner_tracking", made.ms);
    times_.add("cpu.corner_tracking", made.cpu_ms);
  }
  return made;
}

std::optional<core::SE3> DynamicPipeline::initialPose(const dynamic::ImagePyramid& current,
                                                      const std::vector<dynamic::PointTrack>& tracks,
                                                      std::optional<dynamic::PoseModel>& model) {
  core::Stopwatch watch;
  const double cpu = threadCpuMs();
  const core::PinholeCamera& camera = slam_.sensor()->camera();
  // Model 1: the reference keyframe's keypoints that carry map points, tracked by LK into this frame.
  dynamic::PoseCorrespondences from_keyframe;
  const std::shared_ptr<const tracking::ReferenceKeyFrameView> reference = state_.tracking_view.reference_keyframe;
  for (const auto& [id, keyframe] : state_.keyframe_pyramids) {
    if (!reference || id != reference->id) continue;
    const tracking::ReferenceKeyFrameView& view = *reference;
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
    tracking.forward_backward_check = false;  // its EPnP RANSAC rejects the tracks that went astray
    // The keyframe keypoints are undistorted; LK on the raw keyframe image needs them raw.
    from_keyframe = dynamic::keyframeCorrespondences({keyframe, current}, camera.distort(pixels), points_w,
                                                     camera, tracking);
    break;
  }
  // Model 2: last-frame corners lifted with the last depth and pose (Eq. 6). Model 3: constant velocity. Both need
  // the last frame's pose: after a lost frame model 1 stands alone (it needs only the reference keyframe), and its
  // pose is where the tracker's recovery searches the nearby map first.
  dynamic::PoseCorrespondences from_last;
  core::SE3 T_cw_last = core::SE3::Identity();
  std::optional<core::SE3> velocity;
  if (state_.last) {
    const LastFrame& last = *state_.last;
    // Temporal evidence (Dynamic.Temporal.excludeFromFits, as in the fits of the judgement): see tracksOffMask.
    const std::vector<dynamic::PointTrack> fit_tracks =
        options_.temporal.exclude_last_mask_from_fits ? dynamic::tracksOffMask(tracks, last.dynamic_mask) : tracks;
    const auto lifted = dynamic::backProjectTracks(fit_tracks, last.depth, last.T_cw, camera, options_.reprojection);
    from_last = dynamic::lastFrameCorrespondences(fit_tracks, lifted, camera);
    T_cw_last = last.T_cw;
    velocity = state_.tracking_view.velocity;
  }
  const dynamic::InitialPoseResult result = dynamic::estimateInitialPose(from_keyframe, from_last, T_cw_last, velocity,
                                                                         camera, options_.initial_pose);
  times_.add("dynamic.initial_pose", watch.elapsedMs());
  times_.add("cpu.initial_pose", threadCpuMs() - cpu);
  if (spdlog::should_log(spdlog::level::debug)) {
    std::string line;
    for (const dynamic::PoseCandidate& c : result.candidates)
      line += c.valid ? fmt::format(" {}: {} own, {} common inliers, {} cells;", dynamic::toString(c.model),
                                    c.own_inliers, c.common_inliers, c.common_cells)
                      : fmt::format(" {}: none;", dynamic::toString(c.model));
    spdlog::debug("frame {}: initial pose{} {} correspondences; {}", state_.processed, line, result.common_size,
                  result.ok ? "chosen: " + dynamic::toString(result.model) : std::string("no pose"));
  }
  if (!result.ok) return std::nullopt;
  model = result.model;
  return result.T_cw;
}

PersonMaskCarrier::Masks DynamicPipeline::personMasks(FrameSlot& slot,
                                                     const std::vector<dynamic::PointTrack>& tracks) {
  const FrameNumber base = options_.prior.baseFor(slot.number);
  const std::shared_future<segmentation::SegmentationResult>& pending = scheduler_.slot(base).segmentation;
  core::require(pending.valid(), "DynamicPipeline: the segmentation of frame " + std::to_string(base) + " that frame " +
                                     std::to_string(slot.number) + " needs was never scheduled");
  if (state_.person_masks->startsFrom(base)) {
    // A live source does not wait for a late network while the current masks may still be carried one frame on.
    if (!wait_for_segmentation_ && state_.person_masks->canCarry(slot.number) &&
        pending.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      ++segmentation_late_frames_;
      return state_.person_masks->carryOn(slot.number, dynamic::FrameFlow{tracks});
    }
    core::Stopwatch wait;
    const segmentation::SegmentationResult& segmented = pending.get();
    times_.add("dynamic.segmentation_wait", wait.elapsedMs());
    times_.add("dynamic.segmentation", segmented.segment_ms);
    times_.add("cpu.segmentation", segmented.segment_cpu_ms);
  }
  PersonMaskCarrier::Masks masks = state_.person_masks->masksFor(slot.number, pending.get(), dynamic::FrameFlow{tracks});
  // Audited: every frame not served by a detection of its own (carried masks, and masks of carried boxes).
  if (options_.prior.audit_predictions && (base != slot.number || !pending.get().detected))
  {
    prior_audit_.push_back(auditPrediction(masks, slot.audit_segmentation.get()));
    spdlog::debug("frame {}: person mask from frame {} ({}) against the networks' own: IoU {:.3f}, covered {:.3f}",
                  slot.number, base, pending.get().detected ? "detected" : "boxes carried", prior_audit_.back().iou,
                  prior_audit_.back().covered);
  }
  return masks;
}

cv::Mat DynamicPipeline::judge(dynamic::FrontEndInput input) {
  core::Stopwatch watch;
  const double cpu = threadCpuMs();
  dynamic::FrontEndResult judged = front_end_.process(input);
  times_.add("dynamic.front_end", watch.elapsedMs());
  times_.add("cpu.front_end", threadCpuMs() - cpu);
  for (const auto& [stage, ms] : judged.timings_ms) times_.add("dynamic." + stage, ms);
  return std::move(judged.mask);
}

void DynamicPipeline::track(const TrackInput& input, ProcessedFrame& out) {
  const double cpu = threadCpuMs();
  out.slam = slam_.track(input);
  times_.add("cpu.track", threadCpuMs() - cpu);
  const int extracted = out.slam.keypoints + out.slam.removed_dynamic;
  if (extracted > 0) out.removed_fraction = static_cast<double>(out.slam.removed_dynamic) / extracted;
  removed_fractions_.push_back(out.removed_fraction);
}

void DynamicPipeline::remember(const ProcessedFrame& out, FrameMotionInput motion) {
  state_.tracking_view = out.slam.view;  // also after a lost frame: the next frame's initial pose starts from it
  const tracking::TrackResult& result = out.slam.track;
  if (result.state != tracking::TrackingState::kOk) {
    state_.last.reset();  // a lost frame's pose would poison the reprojection test of the next one
    state_.baseline_history.clear();
    return;
  }
  // The long-baseline tracks read the frame's grey image and pyramid ten frames on (shared, not copied).
  const bool tracks = options_.baseline_tracks.enabled;
  state_.baseline_history.add({out.frame.depth, tracks ? motion.gray : cv::Mat(),
                            tracks ? motion.pyramid : dynamic::ImagePyramid(), result.T_cw});
  const bool geometry = scheduler_.tasks().geometry;
  if (geometry && (result.new_keyframe || result.initialized_map)) {
    state_.keyframe_pyramids.emplace_back(out.slam.view.reference_kf, motion.pyramid);
    if (state_.keyframe_pyramids.size() > kKeyFrameImages) state_.keyframe_pyramids.pop_front();
  }
  state_.last = LastFrame{std::move(motion.gray),    out.frame.depth,           out.dynamic_mask,
                          std::move(motion.pyramid), std::move(motion.corners), result.T_cw};
}

FrameNumber DynamicPipeline::firstSlotNeeded() const {
  // The next frame's person masks start from (or continue) the segmentation of baseFor(next); later frames' bases
  // are no older.
  return options_.prior.baseFor(state_.processed);
}

ProcessedFrame DynamicPipeline::processNext() {
  core::require(waiting() > 0, "DynamicPipeline::processNext: no frame was pushed");
  FrameSlot& slot = scheduler_.slot(state_.processed);
  ProcessedFrame out;
  out.frame = slot.frame;
  const StageATasks& tasks = scheduler_.tasks();
  if (!tasks.segmentation) slot.dilated_prior_mask.set_value(cv::Mat());
  const cv::Mat caller_mask = takeCallerMask(slot.number);

  FrameMotionInput motion = takeMotion(slot);  // 1
  double stage_a_cpu = motion.cpu_ms;
  FrameCornerTracks corner_tracks;
  if (scheduler_.tasks().geometry) corner_tracks = takeCornerTracks(slot);  // 2
  TrackInput track_input;
  track_input.timestamp = slot.frame.timestamp;
  track_input.depth = slot.frame.depth;
  // The initial-pose models (step 4) of the next frame read the reference keyframe's points.
  track_input.reference_keyframe_view = tasks.geometry;
  if (options_.mode != dynamic::DynamicMode::kNone) {
    dynamic::FrontEndInput input;
    input.gray = motion.gray;
    input.bgr = slot.frame.bgr;
    input.depth = slot.frame.depth;
    std::vector<dynamic::PointTrack> tracks;
    if (state_.last) {
      const LastFrame& last = *state_.last;
      input.last_gray = last.gray;
      input.last_depth = last.depth;
      input.T_cw_last = last.T_cw;
      input.last_mask = last.dynamic_mask;
      input.T_cw_initial = last.T_cw;
      if (const auto* baseline = state_.baseline_history.baseline()) {
        input.baseline_depth = baseline->depth;
        input.baseline_gray = baseline->gray;
        input.baseline_pyramid = baseline->pyramid;
        input.pyramid = motion.pyramid;
        input.T_cw_baseline = baseline->T_cw;
      }
      if (tasks.geometry) {
        // Stage A tracked the corners of the frame pushed before this one, which is the last frame here: every
        // pushed frame is processed, in order, and state_.last is that frame whenever it was tracked.
        core::require(corner_tracks.made, "DynamicPipeline: frame " + std::to_string(slot.number) +
                                              " has no corner tracks from the frame before it");
        tracks = std::move(corner_tracks.tracks);
        input.tracks = &tracks;
      }
    }
    // The person masks (4) need only the corner tracks, so they are made before the initial pose (3), which does
    // not read them: the next frame's masked extraction in stage A waits for this hand-off.
    if (tasks.segmentation) {
      PersonMaskCarrier::Masks masks = personMasks(slot, tracks);  // 3
      slot.dilated_prior_mask.set_value(masks.dilated);            // hand-off to stage A of the next frame
      input.prior_mask = std::move(masks.dilated);
      out.prior_mask = std::move(masks.mask);
    }
    if (!caller_mask.empty()) input.prior_mask = mergedMask(input.prior_mask, caller_mask);
    if (tasks.geometry) {
      // After a lost frame (no last frame) the reference keyframe's model stands alone.
      std::optional<dynamic::PoseModel> model;
      track_input.initial_T_cw = initialPose(motion.pyramid, tracks, model);  // 4
      out.initial_pose_model = model;
      if (track_input.initial_T_cw && state_.last) input.T_cw_initial = *track_input.initial_T_cw;
    }
    std::optional<FramePartition> partition;
    if (tasks.geometry) {
      core::Stopwatch wait;
      partition = slot.partition.get();
      times_.add("dynamic.partition_wait", wait.elapsedMs());
      stage_a_cpu += partition->cpu_ms;
      input.partition = &partition->partition;
    }
    track_input.dynamic_mask = judge(std::move(input));  // 5
    out.dynamic_mask = track_input.dynamic_mask;
  }
  if (!caller_mask.empty()) {
    // The front end's judgement keeps the prior regions in modes prior and full; in the other modes this is where
    // the caller's mask comes in.
    track_input.dynamic_mask = mergedMask(track_input.dynamic_mask, caller_mask);
    out.dynamic_mask = track_input.dynamic_mask;
  }
  core::Stopwatch wait;
  SlotOrbFeatures features = slot.features.get();
  times_.add("dynamic.features_wait", wait.elapsedMs());
  out.keypoints.reserve(features.features.keypoints.size());
  for (const cv::KeyPoint& k : features.features.keypoints) out.keypoints.push_back(k.pt);
  stage_a_cpu += features.cpu_ms;
  if (tasks.masked_extraction) times_.add("dynamic.extraction_handoff_wait", features.handoff_wait_ms);
  times_.add("cpu.prepare", stage_a_cpu);
  track_input.features = std::move(features.features);
  track(track_input, out);  // 6
  slot.map_ready.set_value(out.slam.view.state != tracking::TrackingState::kNotInitialized);
  remember(out, std::move(motion));  // 7
  ++state_.processed;
  processed_.store(state_.processed);
  scheduler_.release(firstSlotNeeded());
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
  if (segmentation_late_frames_ > 0)
    spdlog::info("person network late on {} frames: their masks were carried on from the segmentation before",
                 segmentation_late_frames_);
  scheduler_.closeSegmentation();
  slam_.finish();
}

}  // namespace amos::system
