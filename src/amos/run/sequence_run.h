#pragma once
// Runs the SLAM system over a whole TUM/Bonn-layout sequence or a live camera: the run shared by `amos-slam run`,
// the end-to-end tests and the benchmarks. Settings come from the config module (config/slam_options.h). The
// run's loop is the controller's (controller.h); what is made of the frames is its observers': ground truth, when
// the sequence has it, is evaluated (trajectory_evaluation.h); ground-truth mover masks, when the sequence has
// them (synthetic sequences: masks.txt, masks/, instances.json), score the front end's dynamic mask
// (mask_scoring.h); --save-masks writes the masks (mask_writing.h) and --record the frames (recording.h).
//
// Frames come from an io::FrameSource chosen by SequenceRunOptions::source: the folder read as fast as the
// pipeline takes it (the default), the folder replayed at its recorded rate (realtime), or a live camera. A frame
// that arrives while the pipeline is busy replaces the waiting one (the source counts it as dropped). The
// trajectory holds the processed frames; RunInfo::source says how many were delivered, processed and dropped and
// how long each processed frame took from its arrival to its pose.
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "amos/api/engine.h"
#include "amos/config/settings.h"
#include "amos/core/stop_request.h"
#include "amos/io/trajectory.h"
#include "amos/report/run_report.h"
#include "amos/run/controller.h"
#include "amos/run/run_observer.h"
#include "amos/system/dynamic_pipeline.h"
#include "amos/system/slam_system.h"

namespace amos::run {

enum class FrameSourceKind {
  kFolder,    // sequence_dir as fast as possible (io::SequenceReader)
  kRealtime,  // sequence_dir at its recorded time stamps (io::RealtimeReplay)
  kCamera,    // a live camera named by `camera` (sequence_dir unused; no evaluation)
  kBag,       // sequence_dir is a ROS 1 bag, read as fast as possible (bag_source.h; AMOS_WITH_ROS builds)
};

// "folder" | "realtime" | the camera's driver name ("openni2") | "bag".
std::string sourceKindName(FrameSourceKind kind, const std::string& camera);

struct CameraSpec {
  std::string driver;  // "openni2"
  std::string uri;     // "" = any device
};
// Parses `--camera DRIVER[:URI]` (the URI is everything after the first colon); throws core::Error for a driver
// this program does not know.
CameraSpec parseCameraSpec(const std::string& spec);

struct SequenceRunOptions {
  FrameSourceKind source = FrameSourceKind::kFolder;
  std::string sequence_dir;
  std::string camera;          // --camera: "openni2" or "openni2:URI" (FrameSourceKind::kCamera)
  // FrameSourceKind::kBag: --rgb-topic, --depth-topic, --camera-info-topic ("" = the known drivers' names,
  // rosbag/bag_topics.h).
  std::string rgb_topic, depth_topic, camera_info_topic;
  // FrameSourceKind::kBag: --groundtruth-topic (the ground truth from this topic instead of a groundtruth.txt
  // beside the bag; rosbag/ground_truth_topic.h) and, for a tf2_msgs/TFMessage topic, the frames of the pose.
  std::string groundtruth_topic;
  std::string groundtruth_parent_frame = "/world", groundtruth_child_frame = "/kinect";
  std::string record_dir;      // --record: write every processed frame there in TUM layout ("" = do not)
  std::string config_label;    // recorded in stats.json
  std::string mode = "none";   // dynamic front end: none | prior | geometry | full (the CLI defaults to full)
  std::string models_dir;      // --models: segmentation model folder (see segmentation/model_locator.h)
  bool deterministic = false;
  // --strict: a frame that cannot be read ends the run with that error (io::ReaderOptions::strict); by default it
  // is skipped and counted (RunInfo::skipped_frames).
  bool strict = false;
  std::size_t max_frames = 0;  // 0 = all
  std::size_t first_frame = 0;  // --first-frame: skip the sequence's frames before this one (0-based)
  // --load-map: start from this saved map (system::SlamSystem::loadMap) instead of an empty one ("" = do not);
  // --localize: only track against it (tracking::TrackerOptions::localization_only).
  std::string load_map;
  bool localize = false;
  // --save-masks: write every frame's final dynamic mask to <masks_output_dir>/masks/ and overlays of
  // overlay_count evenly spaced frames to <masks_output_dir>/overlays/ (see mask_outputs.h). "" = do not.
  std::string masks_output_dir;
  std::size_t overlay_count = 8;
  // The output folder: trajectory_live.txt and frames.tsv are appended there frame by frame (live_log.h), so any
  // end of the program leaves the frames tracked until then. "" = not written.
  std::string live_log_dir;
  std::function<void(const SequenceProgress&)> on_frame;  // called after every frame (progress display)
  // When set, the run ends after the frame being processed once a stop is requested (SIGINT / SIGTERM), and a
  // paced or live source's wait for its next frame ends at once: RunInfo::end is then kInterrupted, and everything
  // is finished and kept as at the end of the stream.
  core::StopRequest* stop = nullptr;
  // Called in the mapping thread after each keyframe is mapped (system::SlamOptions::after_keyframe).
  mapping::KeyFrameHook after_keyframe;
  // Watch the run (live viewer, report recorder; run_observer.h). Not owned; they must outlive the call.
  std::vector<RunObserver*> observers;
};

// The settings as a run with `options` uses them: the options that are also settings keys replace those keys'
// values (mode: Dynamic.mode; the CLI's --mode always sets it). What settings_used.yaml holds.
config::Settings effectiveSettings(const config::Settings& settings, const SequenceRunOptions& options);

struct SequenceRunResult {
  // The SLAM system (finished: mapping stopped) and the front end around it, as amos::Slam makes them.
  std::unique_ptr<api::Engine> engine;
  system::SlamSystem& slam() const { return engine->slam(); }
  system::DynamicPipeline& pipeline() const { return engine->pipeline(); }
  report::RunInfo info;                      // wall time, evaluation when there is ground truth, how it ended
  std::vector<io::StampedPose> trajectory;
  // The error that ended the run early (info.end.status kFailed), or null.
  std::exception_ptr failure;
  void rethrowFailure() const;
};

// Errors before the first frame (settings, models, the camera, the sequence index) are thrown. An error during the
// loop (a frame that cannot be read with `strict`, a failure of a stage-A lane or of the mapping thread) ends the
// run like a stop does: the frames processed so far are finished, evaluated and returned, with the error in
// SequenceRunResult::failure (rethrowFailure()) and RunInfo::end; so the caller can still write the outputs.
SequenceRunResult runSequence(const config::Settings& settings, const SequenceRunOptions& options);

}  // namespace amos::run
