#pragma once
// Amos-SLAM's public C++ API: an RGB-D SLAM system with a dynamic-object front end, fed one frame at a time.
//
//   amos::Options options;
//   options.settings_file = "configs/tum2.yaml";   // the camera, as for `amos-slam run --config`
//   options.mode = amos::Mode::kFull;
//   amos::Slam slam(options);
//   for (each frame) {
//     amos::FrameResult r = slam.track(bgr, depth, timestamp);
//     if (r.T_wc) use(*r.T_wc);                    // empty when the frame was not tracked
//   }
//   slam.finish();
//   slam.writeTrajectory("trajectory.txt");        // what `amos-slam run` writes as trajectory.txt
//
// A caller whose frames come from a loop of its own gets `amos-slam run`'s speed with trackFrames() (the next
// frame's per-frame work overlaps the current one's tracking), or with submit() ahead of next().
//
// Pose convention (the one used throughout): T_wc is the 4x4 rigid transform (Eigen::Matrix4d, column-major as
// Eigen stores it) that maps a point from the camera frame into the world frame, p_w = T_wc * p_c; the camera looks
// along +z, x right, y down; the world frame is the first tracked camera's frame (or the loaded map's). Times are
// seconds, as given to track().
//
// Errors: bad settings or overrides, a missing model, a frame of the wrong size or type, a time stamp that is not
// finite or does not increase, a map file that cannot be read, a call out of order, a moved-from Slam:
// std::runtime_error with a message naming the file, key or argument at fault. Nothing here exits.
//
// Threads and lifetime: every member function may be called from any thread; the calls on one Slam are serialised
// by a mutex of its own (a second thread waits for the first's call to return). Local mapping and segmentation run
// in threads of their own, which the Slam owns and joins in finish() or its destructor. Everything a call returns is
// a value the caller owns (images are copies); the images given to track() are copied, never written, and may be
// reused at once. The library's log: include/amos/logging.h.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "amos/dense_map.h"
#include "amos/logging.h"
#include "amos/version.h"

namespace amos {

// Whether a frame was tracked.
enum class TrackingState {
  kNotInitialized,  // no map yet (the first frame with enough depth starts it)
  kOk,              // tracked: FrameResult::T_wc is this frame's pose
  kLost,            // not tracked (the system relocalises when it can)
};
// "not_initialized" | "ok" | "lost".
const char* toString(TrackingState state);

// The dynamic front end: which of its stages judge what moves (docs/usage.md, "Modes").
enum class Mode {
  kNone,          // none: every keypoint is used (as ORB-SLAM2), apart from the caller's prior masks
  kPrior,         // prior: the person segmentation network's masks
  kGeometry,      // geometry: the geometric stage (motion against the camera's), no network
  kFull,          // full: both
  kFromSettings,  // the settings' Dynamic.mode
};
// "none" | "prior" | "geometry" | "full" | "from_settings".
const char* toString(Mode mode);
// The mode a name gives ("none", "prior", "geometry", "full"; "" = kFromSettings); std::runtime_error otherwise.
Mode parseMode(const std::string& name);

// A pose at a time: the trajectory's entries.
struct StampedPose {
  double timestamp = 0;                                // seconds, as given to track()
  Eigen::Matrix4d T_wc = Eigen::Matrix4d::Identity();  // camera to world
};

// A keyframe of the map, as keyFrames() lists them and takeKeyFrameEvents() / Options::on_keyframe report new ones.
struct KeyFrame {
  std::uint64_t id = 0;  // the map's id of the keyframe (increasing)
  double timestamp = 0;  // of the frame it was made from
  Eigen::Matrix4d T_wc = Eigen::Matrix4d::Identity();  // its pose (when reported as new: when it had been mapped)
};
using KeyFrameEvent = KeyFrame;  // the name of earlier versions

// The install's data folder (segmentation models, ORB vocabulary): given by the CMake package to the programs that
// link AmosSlam::amos_slam, else "" (the library then looks for it itself). Inline, so that the value is the one
// the caller's program was compiled with.
inline std::string installedModelsDir() {
#ifdef AMOS_SLAM_MODELS_DIR
  return AMOS_SLAM_MODELS_DIR;
#else
  return {};
#endif
}

// How a Slam is made. Every member has a default; the settings (settings_file or settings_yaml) are required.
struct Options {
  // The settings (YAML, as configs/*.yaml: camera, DepthMapFactor, ORB, ... see configs/README.md): a file, or,
  // when settings_file is "", the YAML text itself.
  std::string settings_file;
  std::string settings_yaml;
  // Settings keys set over the settings' values, key and value as a settings file writes them, e.g.
  // {{"ORBextractor.nFeatures", "1500"}}. A key the settings do not know is an error naming it.
  std::vector<std::pair<std::string, std::string>> overrides;
  // The dynamic front end.
  Mode mode = Mode::kFromSettings;
  // The folder of the segmentation models and the ORB vocabulary. "" = looked for: the settings'
  // Segmentation.modelsDir, $AMOS_MODELS, the installed data folder (installed_models_dir), ./models,
  // ../shared/models. Errors about a missing model name this option.
  std::string models_dir;
  // The installed data folder, as the program was built against it (see installedModelsDir()).
  std::string installed_models_dir = installedModelsDir();
  // Same input, same trajectory, bit for bit: local mapping runs in lock-step with tracking (slower). Also what
  // `amos-slam run --deterministic` does, so the two give the same trajectory.
  bool deterministic = false;
  // Start from a map saved by saveMap (or `amos-slam run --save-map`) instead of an empty one ("" = do not).
  std::string map_file;
  // Localization mode: only track against the loaded map (map_file, or loadMap before the first frame), never
  // extend it.
  bool localization_only = false;
  // Called in the mapping thread after each new keyframe has been mapped; must return quickly and not call this
  // Slam. (Or poll: Slam::takeKeyFrameEvents.)
  std::function<void(const KeyFrame&)> on_keyframe;
  // Keep the per-frame buffers (megabytes each) in glibc's heap instead of mapping and unmapping them every frame,
  // as `amos-slam` does: raises the process's mmap threshold to 32 MiB and its trim threshold to 512 MiB (mallopt)
  // when the first Slam is made. Process-wide; false leaves the allocator as the program set it (about a tenth
  // more CPU time per frame).
  bool tune_allocator = true;
  // Fuse the dense static map beside tracking (include/amos/dense_map.h), as `amos-slam run --dense`: the tracked
  // frames' static pixels (the dynamic mask, with the caller's prior masks, left out), with the settings' Dense.*
  // keys (and the overrides). denseMap() after finish(), denseSnapshot() while running. Only in a library built
  // with Open3D (denseMappingAvailable()): otherwise true is an error saying so.
  bool dense = false;
};

// What track() / next() return for one frame.
struct FrameResult {
  std::size_t frame = 0;  // 0-based number of the frame in this Slam
  double timestamp = 0;   // as given
  TrackingState state = TrackingState::kNotInitialized;
  // The frame's pose as tracked now (trajectory() has the later corrections); empty unless state is kOk.
  std::optional<Eigen::Matrix4d> T_wc;
  bool new_keyframe = false;  // this frame became a keyframe
  bool relocalized = false;   // tracked again after being lost
  // CV_8U, the frame's size, 255 = judged dynamic (its keypoints were not used): the front end's regions and the
  // caller's prior mask; all zero in mode kNone without a prior mask.
  cv::Mat dynamic_mask;
  int keypoints = 0;          // ORB keypoints extracted
  int keypoints_removed = 0;  // of those, inside the dynamic mask
  // Wall ms of this frame's SLAM stages: ORB extraction, building the frame, tracking (stats.json's "stages").
  double extract_ms = 0, build_ms = 0, track_ms = 0;
};

// One frame handed to trackFrames() (the arguments of track()).
struct InputFrame {
  cv::Mat bgr;         // as track()'s
  cv::Mat depth;       // as track()'s
  double timestamp = 0;
  cv::Mat prior_mask;  // as track()'s (empty = none)
};

// The map and the frames so far.
struct MapSummary {
  std::size_t keyframes = 0;     // keyframes in the map
  std::size_t map_points = 0;    // map points in the map
  std::size_t loops_closed = 0;  // loops closed
  std::size_t frames = 0;        // frames tracked (of every state)
  std::size_t tracked = 0;       // of them, with state kOk
  std::size_t lost = 0;          // of them, with state kLost
};

// What a caller tells writeOutputs about its run for stats.json (docs/usage.md, "Outputs"): where the frames came
// from and how it kept up with them (`amos-slam run` fills the same fields from its own frame source).
struct RunDescription {
  std::string sequence;            // "sequence": where the frames came from (a folder, a bag, a topic, a device)
  std::string config;              // "config": the settings' name (default: Options::settings_file)
  std::string source_kind = "api"; // "source.kind" (run: folder | realtime | bag | openni2)
  std::size_t delivered = 0;       // frames the caller received (0 = the frames tracked)
  std::size_t dropped = 0;         // of those, left out because tracking was busy
  std::vector<double> latency_ms;  // per tracked frame: from its arrival to its pose (empty = not measured)
  // A ground-truth file of these frames (TUM format; the settings' Dataset.groundtruth says whether its poses are
  // the camera's or Bonn's marker's): stats.json then has run's "evaluation" (ATE / RPE of trajectory.txt), as run
  // has against a sequence's groundtruth.txt. "" = none. One that cannot be read, or an evaluation that fails, is
  // a warning (the library's log), and the files are written without it.
  std::string groundtruth_file;
  // Names of the caller's own files in the same folder (e.g. a saved map): listed in run_manifest.json beside
  // writeOutputs' own, so that `amos-slam run --overwrite` on the folder may replace them.
  std::vector<std::string> other_outputs;
};

// The SLAM system. Move-only; a moved-from Slam throws std::runtime_error from every member function.
class Slam {
 public:
  // Reads the settings (with the overrides) and loads the models, the vocabulary and the map (Options::map_file).
  explicit Slam(const Options& options);
  // Slam(Options) with these (the models found as for Options' defaults).
  explicit Slam(const std::string& settings_file, Mode mode = Mode::kFromSettings, bool deterministic = false)
      : Slam(makeOptions(settings_file, mode, deterministic)) {}
  // Finishes (finish()) when that was not done.
  ~Slam();
  Slam(Slam&&) noexcept;             // the other Slam is left moved-from
  Slam& operator=(Slam&&) noexcept;  // finishes this one first
  Slam(const Slam&) = delete;
  Slam& operator=(const Slam&) = delete;

  // Tracks one frame. bgr: CV_8UC3 in OpenCV's BGR order; depth: CV_16UC1 raw sensor values (metres = value /
  // DepthMapFactor of the settings) or CV_32FC1 metres (0 or NaN = no depth); both of the settings' Camera.width x
  // Camera.height. timestamp: seconds, finite, greater than the last frame's. prior_mask (optional): what the
  // caller's own detector found, CV_8UC1 of the same size, non-zero = dynamic: its pixels' keypoints are left out
  // and its regions join the front end's as the person network's do. Each argument is checked; a bad one is a
  // std::runtime_error naming it.
  FrameResult track(const cv::Mat& bgr, const cv::Mat& depth, double timestamp, const cv::Mat& prior_mask = {});

  // Tracks every frame `source` gives, in order, until it gives nullopt, and hands each result to `on_result`, both
  // called in the caller's thread (`source` one frame ahead of `on_result`). The next frame's
  // per-frame work (features, superpixels, segmentation) runs in the library's threads while the current one is
  // tracked, as `amos-slam run` reads a folder; the results are track()'s (bit-identical with `deterministic`).
  // Returns the number of frames tracked. An exception from `source` or `on_result` ends it, the frames taken
  // still tracked (their poses reach trajectory()), and is rethrown.
  std::size_t trackFrames(const std::function<std::optional<InputFrame>()>& source,
                          const std::function<void(const FrameResult&)>& on_result);

  // track() in two halves, for a caller that has the next frame before the current one's result is needed:
  // submit() checks and copies the frame and returns at once, its per-frame work starting in the library's
  // threads; next() finishes the oldest submitted frame in order and returns its result. At most kMaxPending frames
  // may wait; next() with none waiting is an error.
  static constexpr std::size_t kMaxPending = 4;
  // Hands a frame over (the arguments as track()'s).
  void submit(const cv::Mat& bgr, const cv::Mat& depth, double timestamp, const cv::Mat& prior_mask = {});
  // The oldest submitted frame's result.
  FrameResult next();
  // Submitted, not yet returned by next().
  std::size_t pending() const;

  // Starts from a saved map; only before the first frame.
  void loadMap(const std::string& path);
  // Tracks the frames still pending (their results are not returned, their poses reach trajectory()), lets local
  // mapping finish its queue and stops it; frames are refused after. Idempotent.
  void finish();
  // Whether finish() was called.
  bool finished() const;
  // Writes the map (after finish(): the map local mapping has settled).
  void saveMap(const std::string& path) const;
  // Writes into `dir` (created if needed) what `amos-slam run` writes there for the same frames, by the same code:
  // trajectory.txt (as writeTrajectory), keyframes.txt, map.ply, stats.json (counts, per-stage times, the share of
  // keypoints removed per frame, depth dropouts, wall time from the first frame to finish(), `run`'s description;
  // the evaluation with RunDescription::groundtruth_file), settings_used.yaml (the settings with the overrides and the mode), the per-frame files
  // trajectory_live.txt (each tracked frame's pose at tracking time, as FrameResult::T_wc) and frames.tsv (one line
  // per frame: index, time stamp, state, inliers, keyframe, ms since the frame before), kept by the Slam as it
  // tracks, and run_manifest.json (the names written, with RunDescription::other_outputs). Not report.html (the
  // viewer module's, `amos-slam run` only). After finish() these are the final files; before, those of the frames
  // so far. Each file is written under a temporary name and renamed; an error names the file that cannot be
  // written.
  void writeOutputs(const std::string& dir, const RunDescription& run = {}) const;
  // The names writeOutputs writes.
  static std::vector<std::string> outputNames();

  // One pose per tracked frame (T_wc), with the map's corrections up to now (bundle adjustment, loop closing): after
  // finish() it is the final trajectory, what `amos-slam run` writes. In localization mode only the localised frames.
  std::vector<StampedPose> trajectory() const;
  // trajectory() as a TUM file ("timestamp tx ty tz qx qy qz qw"), as `amos-slam run` writes trajectory.txt.
  void writeTrajectory(const std::string& path) const;
  // The keyframes and their current poses, by id.
  std::vector<KeyFrame> keyFrames() const;
  // The keyframes mapped since the last call (polling instead of Options::on_keyframe).
  std::vector<KeyFrame> takeKeyFrameEvents();
  // The good map points' world positions.
  std::vector<Eigen::Vector3d> mapPoints() const;
  // Counts of the map and the frames.
  MapSummary summary() const;

  // The dense map (Options::dense), fused with the final trajectory (trajectory() after finish()) from the frames
  // kept: what `amos-slam run --dense` writes for the same frames and settings. After finish(); the fusion takes
  // a while (it runs anew each call). An error without Options::dense or before finish().
  DenseMap denseMap() const;
  // The live volume's surface so far (tracking poses, every Dense.liveEveryth kept frame fused), or nullopt before
  // the first one (or with Dense.liveEvery 0). An error without Options::dense.
  std::optional<DenseSnapshot> denseSnapshot() const;
  // The floor plan of that live surface (the floor found and the grid built from it as denseMap() does from the
  // final surface; the cameras placed by trajectory()), or nullopt before the first live surface or while no floor
  // is found in it. Takes a while on a large surface (tens of ms): for a caller's own rate, not every frame. An
  // error without Options::dense.
  std::optional<OccupancyGrid> denseLiveGrid() const;
  // The settings' camera size (Camera.width x Camera.height), which every frame must have.
  cv::Size imageSize() const;

 private:
  static Options makeOptions(const std::string& settings_file, Mode mode, bool deterministic) {
    Options o;
    o.settings_file = settings_file;
    o.mode = mode;
    o.deterministic = deterministic;
    return o;
  }
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos
