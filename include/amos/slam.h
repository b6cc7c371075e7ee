#pragma once
// Amos-SLAM's public C++ API: an RGB-D SLAM system with a dynamic-object front end, fed one frame at a time.
//
//   amos::Options options;
//   options.settings_file = "configs/tum2.yaml";   // the camera, as for `amos-slam run --config`
//   options.mode = "full";
//   amos::Slam slam(options);
//   for (each frame) {
//     amos::FrameResult r = slam.track(bgr, depth, timestamp);
//     if (r.state == amos::TrackingState::kOk) use(r.T_wc);
//   }
//   slam.finish();
//   slam.writeTrajectory("trajectory.txt");        // what `amos-slam run` writes as trajectory.txt
//
// Pose convention (the one used throughout): T_wc is the 4x4 rigid transform (Eigen::Matrix4d, column-major as
// Eigen stores it) that maps a point from the camera frame into the world frame, p_w = T_wc * p_c; the camera looks
// along +z, x right, y down; the world frame is the first tracked camera's frame (or the loaded map's). Times are
// seconds, as given to track().
//
// Errors: bad settings, a missing model, a frame of the wrong size or type, a map file that cannot be read, a call
// out of order: std::runtime_error with a message naming the file, key or argument at fault. Nothing here exits.
//
// Threads and lifetime: a Slam is used from one thread at a time (track, finish, saveMap, ... are not concurrent);
// local mapping and segmentation run in threads of their own, which the Slam owns and joins in finish() or its
// destructor. Everything a call returns is a value the caller owns (images are copies); the images given to
// track() are copied, never written, and may be reused at once.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "amos/version.h"

namespace amos {

enum class TrackingState {
  kNotInitialized,  // no map yet (the first frame with enough depth starts it)
  kOk,              // tracked: T_wc is this frame's pose
  kLost,            // not tracked: T_wc is the last pose known (the system relocalises when it can)
};
const char* toString(TrackingState state);  // "not_initialized" | "ok" | "lost"

struct StampedPose {
  double timestamp = 0;
  Eigen::Matrix4d T_wc = Eigen::Matrix4d::Identity();
};

struct KeyFrameEvent {
  std::uint64_t id = 0;
  double timestamp = 0;  // of the frame it was made from
  Eigen::Matrix4d T_wc = Eigen::Matrix4d::Identity();  // its pose when it had been mapped
};

// The install's data folder (segmentation models, ORB vocabulary): given by the CMake package to the programs that
// link AmosSlam::amos_slam, else "" (the library then looks for it itself).
inline std::string installedModelsDir() {
#ifdef AMOS_SLAM_MODELS_DIR
  return AMOS_SLAM_MODELS_DIR;
#else
  return {};
#endif
}

struct Options {
  // The settings (YAML, as configs/*.yaml: camera, DepthMapFactor, ORB, ... see configs/README.md): a file, or,
  // when settings_file is "", the YAML text itself.
  std::string settings_file;
  std::string settings_yaml;
  // The dynamic front end: "none" | "prior" | "geometry" | "full" ("" = the settings' Dynamic.mode).
  std::string mode;
  // The folder of the segmentation models and the ORB vocabulary. "" = the installed data folder (unless the
  // settings' Segmentation.modelsDir or $AMOS_MODELS name one), then ./models and ../shared/models.
  std::string models_dir;
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
  std::function<void(const KeyFrameEvent&)> on_keyframe;
};

struct FrameResult {
  std::size_t frame = 0;  // 0-based number of the frame in this Slam
  double timestamp = 0;
  TrackingState state = TrackingState::kNotInitialized;
  Eigen::Matrix4d T_wc = Eigen::Matrix4d::Identity();  // as tracked now (trajectory() has the later corrections)
  bool new_keyframe = false;  // this frame became a keyframe
  bool relocalized = false;
  // CV_8U, the frame's size, 255 = judged dynamic (its keypoints were not used); all zero in mode "none".
  cv::Mat dynamic_mask;
  int keypoints = 0;          // ORB keypoints extracted
  int keypoints_removed = 0;  // of those, inside the dynamic mask
};

struct MapSummary {
  std::size_t keyframes = 0, map_points = 0, loops_closed = 0;
  std::size_t frames = 0, tracked = 0, lost = 0;
};

class Slam {
 public:
  // Reads the settings and loads the models, the vocabulary and the map (Options::map_file).
  explicit Slam(const Options& options);
  // Same as Options{settings_file} with these.
  explicit Slam(const std::string& settings_file, const std::string& mode = "", bool deterministic = false);
  ~Slam();  // finish()es when that was not done
  Slam(Slam&&) noexcept;
  Slam& operator=(Slam&&) noexcept;
  Slam(const Slam&) = delete;
  Slam& operator=(const Slam&) = delete;

  // Tracks one frame. bgr: CV_8UC3 in OpenCV's BGR order; depth: CV_16U raw sensor values (metres = value /
  // DepthMapFactor of the settings) or CV_32F metres (0 or NaN = no depth); both of the settings' Camera.width x
  // Camera.height. Time stamps should increase.
  FrameResult track(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);

  // track() in two halves, for a caller that has the next frame before the current one's result is needed (a
  // recorded sequence): submit() checks and copies the frame and returns at once, its per-frame work (features,
  // segmentation) starting in the library's threads; next() finishes the oldest submitted frame in order and
  // returns its result. Submitting frame k+1 before next() returns frame k lets the two overlap, as
  // `amos-slam run` does over a folder; the results are the same as track()'s (bit-identical with
  // `deterministic`). At most kMaxPending frames may wait; next() with none waiting is an error.
  static constexpr std::size_t kMaxPending = 4;
  void submit(const cv::Mat& bgr, const cv::Mat& depth, double timestamp);
  FrameResult next();
  std::size_t pending() const;  // submitted, not yet returned by next()

  // Starts from a saved map; only before the first frame.
  void loadMap(const std::string& path);
  // Lets local mapping finish its queue and stops it; track() is refused after. Idempotent.
  void finish();
  // Writes the map (after finish(): the map local mapping has settled).
  void saveMap(const std::string& path) const;

  // One pose per tracked frame (T_wc), with the map's corrections up to now (bundle adjustment, loop closing): after
  // finish() it is the final trajectory, what `amos-slam run` writes. In localization mode only the localised frames.
  std::vector<StampedPose> trajectory() const;
  // trajectory() as a TUM file ("timestamp tx ty tz qx qy qz qw"), as `amos-slam run` writes trajectory.txt.
  void writeTrajectory(const std::string& path) const;
  // The keyframes' current poses.
  std::vector<StampedPose> keyFrames() const;
  // The keyframes mapped since the last call (polling instead of Options::on_keyframe).
  std::vector<KeyFrameEvent> takeKeyFrameEvents();
  // The good map points' world positions.
  std::vector<Eigen::Vector3d> mapPoints() const;
  MapSummary summary() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amos
