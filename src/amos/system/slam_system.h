#pragma once
// The SLAM core as one object, fed by one call: track() takes a frame whose ORB features were already extracted
// (stage A of the pipeline, frame_scheduler.h, owns the extractor) together with what the dynamic front end made of
// it (the dynamic mask, an initial pose), builds the frame (undistortion, depth, removal of the dynamic keypoints)
// and tracks it in the caller's thread, while local mapping runs in its own thread. It returns the pose and a
// TrackingView: the tracking state the front end needs for the next frame (state, velocity, reference keyframe),
// as values. Nothing outside reaches into the tracker, so the tracker's state can change only through track(), and
// the front end sees exactly what the core chose to show it.
//
// Every frame's pose is stored relative to its reference keyframe (T_cr), and trajectory() composes it with the
// keyframe's current pose, so bundle-adjustment corrections made after a frame was tracked reach the output
// trajectory (as ORB-SLAM2 does).
//
// A failure of the mapping thread (local mapping or loop closing) ends the mapping and reaches the caller: track()
// rethrows it at the next frame (core::Error naming the keyframe and the cause); workerFailure() has it too, also
// one that happened while finish() let the mapping drain its queue.
#include <opencv2/core.hpp>

#include <exception>
#include <memory>
#include <optional>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/stage_timer.h"
#include "amos/feature/orb_extractor.h"
#include "amos/io/dataset.h"
#include "amos/io/trajectory.h"
#include "amos/loop/loop_closer.h"
#include "amos/map/map.h"
#include "amos/map/sensor.h"
#include "amos/mapio/map_file.h"
#include "amos/mapping/local_mapper.h"
#include "amos/place/keyframe_database.h"
#include "amos/tracking/tracker.h"

namespace amos::system {

struct SlamOptions {
  core::CameraIntrinsics camera;       // Camera.*
  map::SensorOptions sensor;           // Camera.bf, ThDepth
  feature::OrbOptions orb;             // ORBextractor.*: the scale pyramid of the features track() is given
  map::CovisibilityOptions covisibility;  // Mapping.covisibilityMinWeight
  tracking::TrackerOptions tracking;   // Tracking.*, Matching.*, Relocalization.*
  mapping::LocalMappingOptions mapping;  // Mapping.*, LocalBA.*
  loop::LoopClosingOptions loop;         // Loop.*
  // Place.vocabulary, loaded: keyframes get bag-of-words vectors in a database that relocalisation and loop
  // detection query (place/). Null: both rank keyframes by thumbnails.
  std::shared_ptr<const place::Vocabulary> vocabulary;
  // System.deterministic: local mapping in lock-step with tracking (each keyframe fully processed before the
  // next frame is tracked), so the same input gives a bit-identical trajectory.
  bool deterministic = false;
  // Called in the mapping thread after each keyframe is mapped (loop closing done), for observers and tests. An
  // exception thrown from it is a mapping failure like any other (see SlamSystem::track).
  mapping::KeyFrameHook after_keyframe;
  void check() const;
};

struct ExtractedFeatures {
  cv::Mat gray;                         // the grey image they were detected in (CV_8U)
  std::vector<cv::KeyPoint> keypoints;  // distorted, as detected
  cv::Mat descriptors;
  double extract_ms = 0;
};

// One frame as the pipeline hands it to the core: its depth, the ORB features of its grey image, and the dynamic
// front end's results (paper Sec. III).
struct TrackInput {
  double timestamp = 0;
  cv::Mat depth;                          // CV_32F metres
  ExtractedFeatures features;             // extracted with SlamOptions::orb (the sensor's scale pyramid)
  cv::Mat dynamic_mask;                   // CV_8U, 255 = dynamic; keypoints there are removed before matching
  std::optional<core::SE3> initial_T_cw;  // initial pose from outside (replaces / competes with the motion model)
  // Whether the output's view carries the reference keyframe's keypoints and points: a copy of each keypoint
  // under the map's lock, so only for a caller that reads them (the geometric stage's initial-pose models).
  bool reference_keyframe_view = false;
};

// The tracking state after a frame, as values (nothing in it refers into the tracker or the map): what the dynamic
// front end reads of the core before it judges and tracks the next frame.
struct TrackingView {
  tracking::TrackingState state = tracking::TrackingState::kNotInitialized;
  std::optional<core::SE3> velocity;                // constant-velocity motion (T_cur_last), when known
  map::KeyFrameId reference_kf = map::kNoKeyFrame;  // the tracker's reference keyframe
  // Its keypoints and map points (when TrackInput::reference_keyframe_view asked for them, else null). Immutable,
  // so shared: the pipeline keeps it for the next frame while the caller reads the frame's output.
  std::shared_ptr<const tracking::ReferenceKeyFrameView> reference_keyframe;
};

struct FrameOutput {
  tracking::TrackResult track;
  TrackingView view;
  int keypoints = 0, removed_dynamic = 0, with_depth = 0;
  double extract_ms = 0, build_ms = 0, track_ms = 0, total_ms = 0;
};

struct SlamStats {
  std::size_t frames = 0, tracked = 0, lost = 0, not_initialized = 0, relocalized = 0;
  std::size_t keyframes_created = 0, keyframes = 0, map_points = 0;
  mapping::LocalMappingStats mapping;
  std::size_t loops_closed = 0;
};

class SlamSystem {
 public:
  explicit SlamSystem(const SlamOptions& options);
  ~SlamSystem();
  SlamSystem(const SlamSystem&) = delete;
  SlamSystem& operator=(const SlamSystem&) = delete;

  // The one entry point for frames: builds the input's frame and tracks it (see the header comment). Throws
  // core::Error after finish(), for a depth image that is not CV_32F, and with the mapping thread's failure.
  FrameOutput track(const TrackInput& input);

  // Starts from a saved map (mapio/map_file.h) instead of an empty one; call before the first frame. The first
  // frame is then relocalised in it (cold start). Without options.tracking.localization_only the map is extended
  // (new keyframes and points, loop closures with the loaded part); with it, it is only tracked against. Throws
  // core::Error naming the file and the problem (unreadable, truncated, corrupt, another version or calibration).
  mapio::MapFileSummary loadMap(const std::string& path);
  // Writes the map to `path` (call after finish(), so local mapping has settled it).
  mapio::MapFileSummary saveMap(const std::string& path) const;

  // Lets local mapping finish its queue and stops its thread. Further frames are not accepted. Never throws.
  void finish();
  // The failure that stopped the mapping thread, or null.
  std::exception_ptr workerFailure() const;

  // One pose per processed frame (T_wc, TUM convention), composed with the current keyframe poses; none for the
  // frames before the map existed (or before the first frame was localised in a loaded map). In localization
  // mode only the frames localised in the map (a lost frame's pose would be a guess).
  std::vector<io::StampedPose> trajectory() const;
  // Poses of the keyframes in the map (T_wc).
  std::vector<io::StampedPose> keyframeTrajectory() const;
  // World positions of the good map points, by id.
  std::vector<Eigen::Vector3d> mapPointPositions() const;
  SlamStats stats() const;
  const core::StageTimes& times() const { return times_; }

  const SlamOptions& options() const { return options_; }
  map::Map& map() { return *map_; }
  const map::Map& map() const { return *map_; }
  // The map for observers that may outlive this system (the viewer's publisher thread; run/run_observer.h).
  std::shared_ptr<const map::Map> sharedMap() const { return map_; }
  const std::shared_ptr<const map::Sensor>& sensor() const { return sensor_; }
  // The keyframes' bag-of-words database (null without a vocabulary).
  const place::KeyFrameDatabase* places() const { return places_.get(); }

 private:
  struct FrameRecord {
    double timestamp = 0;
    tracking::TrackingState state = tracking::TrackingState::kNotInitialized;
    map::KeyFrameId reference_kf = map::kNoKeyFrame;
    core::SE3 T_cr = core::SE3::Identity();
  };

  SlamOptions options_;
  std::shared_ptr<const map::Sensor> sensor_;
  std::shared_ptr<map::Map> map_;
  core::StageTimes times_;
  std::shared_ptr<place::KeyFrameDatabase> places_;  // null without a vocabulary
  std::unique_ptr<loop::LoopCloser> loop_closer_;  // used by the mapping thread: declared (and outlives) before it
  std::unique_ptr<mapping::LocalMapper> mapper_;
  std::unique_ptr<tracking::Tracker> tracker_;
  std::vector<FrameRecord> records_;
  SlamStats stats_;
  map::FrameId next_frame_id_ = 0;
  bool finished_ = false;
  bool map_loaded_ = false;
};

}  // namespace amos::system
