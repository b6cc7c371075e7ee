#pragma once
// The generator: a preset, a seed and a frame count in, frames out. SequenceGenerator renders any frame on
// demand (frames are independent: every random draw of frame k comes from its own seeded stream), and
// renderSequence() writes a whole sequence in the TUM layout. The same options give byte-identical files.
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "amos/core/pose.h"
#include "amos/synth/movers.h"
#include "amos/synth/presets.h"
#include "amos/synth/renderer.h"
#include "amos/synth/sensor_model.h"

namespace amos::synth {

struct SequenceOptions {
  std::string preset = "walking_xyz";  // synth.preset, see presets.h
  std::uint32_t seed = 1;              // synth.seed: room, textures, camera path details, movers, noise
  int frames = 0;                      // synth.frames: 0 = the preset's default
  bool movers = true;                  // synth.movers: false renders the preset's static counterpart
  std::string photo_dir;               // synth.photo_dir: photographs for posters and screens ("" = none)
  std::string person_cutout_dir;       // synth.person_cutout_dir: rgb/ + mask/ person cut-outs ("" = procedural people)
  double metres_per_texel = 0.004;     // synth.metres_per_texel: texture resolution of walls and floor
  double start_timestamp = 1700000000.0;  // synth.start_timestamp: seconds, first frame's time stamp
  SensorOptions sensor;                   // synth.sensor.*
  void check() const;
};

struct SyntheticFrame {
  int index = 0;
  double timestamp = 0;                    // the colour image's (mid-exposure) time stamp
  double depth_timestamp = 0;              // the depth image's: timestamp + sensor.depth_time_offset_s
  core::SE3 T_wc = core::SE3::Identity();  // ground truth at `timestamp`, camera to world
  cv::Mat bgr;                             // CV_8UC3, as written to rgb/
  cv::Mat depth_raw;                       // CV_16U, as written to depth/ (metres * depth_factor, 0 = no reading)
  cv::Mat depth;                           // CV_32F metres (depth_raw / depth_factor, 0 = no reading)
  cv::Mat exact_depth;                     // CV_32F metres, the scene's true depth (at depth_timestamp) before
                                           //   the sensor model
  cv::Mat mask;                            // CV_16U instance ids as written to masks/ (0 = static), of the
                                           //   colour image (row by row under a rolling shutter)
  std::vector<std::uint16_t> moving;       // instances moving at this instant (> 1 mm over the last 0.1 s)
};

class SequenceGenerator {
 public:
  explicit SequenceGenerator(const SequenceOptions& options);
  ~SequenceGenerator();
  SequenceGenerator(const SequenceGenerator&) = delete;
  SequenceGenerator& operator=(const SequenceGenerator&) = delete;

  int frameCount() const;
  double time(int index) const;       // seconds since the first frame
  double timestamp(int index) const;  // start_timestamp + time(index)
  core::SE3 poseWc(int index) const;
  const Preset& preset() const;
  const SequenceOptions& options() const;
  const std::vector<InstanceInfo>& instances() const;
  const core::CameraIntrinsics& intrinsics() const;

  // The frame as the sensor delivers it, with its ground truth.
  SyntheticFrame render(int index) const;
  // Exact render (no sensor model) with only the chosen layers, e.g. the movers alone, for tests: a global
  // shutter image of frame `index` at its time stamp, or at any time t (seconds since the first frame; the
  // camera path and the movers at t), optionally only the rows of `band`.
  RenderedImage renderExact(int index, bool with_static, bool with_movers, bool with_color) const;
  RenderedImage renderExactAt(double t, bool with_static, bool with_movers, bool with_color,
                              const RowBand& band = {}) const;
  // The movers' geometry at time t seen from camera_position_w (for tests and tools).
  SceneGeometry moverGeometry(double t, const Eigen::Vector3d& camera_position_w) const;
  std::vector<std::uint16_t> movingInstances(double t) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct SequenceSummary {
  int frames = 0;
  double render_ms_per_frame = 0;  // rendering + sensor model
  double write_ms_per_frame = 0;   // PNG encoding and files
  double setup_ms = 0;             // textures, room, assets
  double total_s = 0;
};

// Renders the sequence into output_dir (created if needed) in the TUM layout: rgb/, depth/, masks/, rgb.txt,
// depth.txt, masks.txt, associations.txt, groundtruth.txt, instances.json, static_surface.ply (static_surface.h),
// swept_volume.ply (swept_volume.h).
SequenceSummary renderSequence(const SequenceOptions& options, const std::string& output_dir);

// The sequence of `preset`, `seed` and `frames` (all other options at their defaults), rendered once into
// <cache_root>/<preset>_seed<seed>_<frames> and reused from there: for tests and scripts that need the same short
// sequence many times. It is rendered into a temporary sibling folder and renamed into place, so callers in other
// processes never see a half-rendered sequence. Returns the sequence folder.
std::string cachedSequence(const std::string& cache_root, const std::string& preset, std::uint32_t seed, int frames);

}  // namespace amos::synth
