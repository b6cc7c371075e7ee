#include "amos/system/dynamic_pipeline.h"

#include <opencv2/calib3d.hpp>

#include <functional>
#include <thread>
#include <utility>

#include "amos/core/bounded_queue.h"
#include "amos/core/error.h"
#include "amos/dynamic/initial_pose_models.h"
#include "amos/dynamic/reprojection_scoring.h"

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

}  // namespace

// One thread running preparation jobs in submission order; results come back through futures (an exception of a job
// is rethrown by its future's get()).
class DynamicPipeline::LookAheadWorker {
 public:
  LookAheadWorker() : jobs_(kQueuedJobs), thread_([this] { run(); }) {}
  ~LookAheadWorker() {
    jobs_.close();  // jobs already queued still run: their futures are never left without a value
    thread_.join();
  }
  LookAheadWorker(const LookAheadWorker&) = delete;
  LookAheadWorker& operator=(const LookAheadWorker&) = delete;

  std::future<PreparedFrame> submit(std::function<PreparedFrame()> job) {
    std::packaged_task<PreparedFrame()> task(std::move(job));
    std::future<PreparedFrame> result = task.get_future();
    core::require(jobs_.push(std::move(task)), "DynamicPipeline: look-ahead worker closed");
    return result;
  }

 private:
  // The current and the next frame are the most in flight; room for a few announced-but-skipped ones.
  static constexpr std::size_t kQueuedJobs = 4;
  void run() {
    while (std::optional<std::packaged_task<PreparedFrame()>> job = jobs_.pop()) (*job)();
  }
  core::BoundedQueue<std::packaged_task<PreparedFrame()>> jobs_;
  std::thread thread_;  // last: started once the queue exists
};

DynamicPipeline::DynamicPipeline(SlamSystem& slam, const dynamic::DynamicOptions& options,
                                 std::unique_ptr<dynamic::SegmentationWorker> segmentation)
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

void DynamicPipeline::requestSegmentation(const io::RgbdFrame& frame) {
  for (const Submitted& s : submitted_)
    if (s.index == frame.index && s.image == frame.bgr.data) return;
  submitted_.push_back({frame.index, frame.bgr.data, segmentation_->submit(frame.index, frame.bgr, frame.depth)});
}

bool DynamicPipeline::masksExtraction() const {
  return usesSegmentation() && options_.prior_masked_extraction && !options_.judge_prior_regions;
}

std::shared_future<dynamic::SegmentationResult> DynamicPipeline::takeSegmentation(const io::RgbdFrame& frame) {
  // Results of frames the caller announced but never processed are dropped (the worker still finishes them).
  while (!submitted_.empty() && (submitted_.front().index != frame.index || submitted_.front().image != frame.bgr.data))
    submitted_.pop_front();
  core::require(!submitted_.empty(), "DynamicPipeline: no segmentation was requested for this frame");
  std::shared_future<dynamic::SegmentationResult> result = std::move(submitted_.front().result);
  submitted_.pop_front();
  return result;
}

PreparedFrame DynamicPipeline::prepare(const io::RgbdFrame& frame, bool with_partition,
                                      std::shared_future<dynamic::SegmentationResult> previous_segmentation,
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
  if (masksExtraction() && previous_segmentation.valid()) {
    core::Stopwatch wait;
    const dynamic::SegmentationResult& segmented = previous_segmentation.get();
    prepared.segmentation_wait_ms = wait.elapsedMs();
    const cv::Mat& dynamic = segmented.dilated_mask;
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
                                         const std::shared_future<dynamic::SegmentationResult>& previous_segmentation,
                                         bool map_ready) {
  for (const Preparing& p : preparing_)
    if (p.index == frame.index && p.image == frame.bgr.data) return;
  if (!look_ahead_) look_ahead_ = std::make_unique<LookAheadWorker>();
  // The job holds its own references to the images (cv::Mat headers share the pixels), not to the caller's frame.
  // The partition is made even though whether the frame will have a last frame (and use it) is not known yet.
  preparing_.push_back({frame.index, frame.bgr.data,
                        look_ahead_->submit([this, frame, previous_segmentation, map_ready] {
                          return prepare(frame, usesGeometry(), previous_segmentation, map_ready);
                        })});
}

PreparedFrame DynamicPipeline::takePreparation(const io::RgbdFrame& frame,
                                              const std::shared_future<dynamic::SegmentationResult>& previous_segmentation,
                                              bool map_ready) {
  while (!preparing_.empty() && (preparing_.front().index != frame.index || preparing_.front().image != frame.bgr.data))
    preparing_.pop_front();  // announced but never processed: dropped (the worker still finishes it)
  if (preparing_.empty()) return prepare(frame, false, previous_segmentation, map_ready);
  core::Stopwatch wait;
  PreparedFrame prepared = preparing_.front().result.get();
  preparing_.pop_front();
  times_.add("dynamic.prepare_wait", wait.elapsedMs());
  return prepared;
}

DynamicFrameOutput DynamicPipeline::process(const io::RgbdFrame& frame, const io::RgbdFrame* next) {
  DynamicFrameOutput out;
  // 1. Segmentation of this frame runs in its own thread (it started during the previous call when that call was
  //    given this frame as look-ahead), then the next frame's ...
  std::shared_future<dynamic::SegmentationResult> pending;
  if (usesSegmentation()) {
    requestSegmentation(frame);
    pending = takeSegmentation(frame);
    if (next != nullptr) requestSegmentation(*next);
  }
  // 2. ... while this thread extracts features (or takes them from the look-ahead worker, which then goes on with
  //    the next frame).
  // The map's state after the previous frame: what the look-ahead preparation of the next frame can know.
  const bool map_ready_one_frame_back = slam_.tracker().state() != tracking::TrackingState::kNotInitialized;
  PreparedFrame prepared = takePreparation(frame, previous_segmentation_, map_ready_two_frames_back_);
  if (next != nullptr) requestPreparation(*next, pending, map_ready_one_frame_back);
  previous_segmentation_ = pending;
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
    if (pending.valid()) {
      core::Stopwatch wait;
      const dynamic::SegmentationResult& segmented = pending.get();
      times_.add("dynamic.segmentation_wait", wait.elapsedMs());
      times_.add("dynamic.segmentation", segmented.segment_ms);
      times_.add("cpu.segmentation", segmented.segment_cpu_ms);
      input.prior_mask = segmented.dilated_mask;
      out.prior_mask = segmented.mask;
    }
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
  if (segmentation_) segmentation_->close();
  slam_.finish();
}

}  // namespace amos::system
