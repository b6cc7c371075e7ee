#pragma once
// For tests only (library amos_testing): small synthetic scenes and sequences in memory, with known answers, so
// that tracking, mapping and the SLAM system can be unit-tested without real data (as COLMAP's
// SynthesizeDataset feeds its mapper tests). A scene is a few textured rectangles rendered by synth::Renderer
// (exact depth, exact per-pixel mover ids); a sequence is a scene plus a camera path (T_cw per frame) and, when
// there are movers, their rigid motion per frame.
//
// World frame: the scenes here are built in the camera frame of their first view (x right, y down, z forward),
// so a path that starts at the identity matches the tracker's map, whose world is its first frame.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/io/rgbd_frame.h"
#include "amos/synth/renderer.h"
#include "amos/synth/scene.h"
#include "amos/synth/texture.h"

namespace amos::testing {

// What an RGB-D camera at T_cw sees of a scene.
struct SyntheticView {
  core::SE3 T_cw = core::SE3::Identity();
  cv::Mat bgr;         // CV_8UC3
  cv::Mat gray;        // CV_8U
  cv::Mat depth;       // CV_32F, z in metres, exact to float precision; 0 where nothing was hit
  cv::Mat instance;    // CV_16U: the id of the mover seen at each pixel, 0 = static scene
  cv::Mat mover_mask;  // CV_8U: 255 where a mover is seen (the per-pixel truth of a dynamic mask)
};

// A grey texture (as BGR) of smoothed random noise: rich in corners at every scale, so ORB finds features on it
// from near and far, and distinctive, so they match. `size` in texels; deterministic in `seed`.
cv::Mat noiseTexture(std::uint32_t seed, cv::Size size);
// Single-scale noise: uniform noise smoothed by a Gaussian of blur_texels and stretched to 0..255.
cv::Mat fineNoiseTexture(std::uint32_t seed, cv::Size size, double blur_texels);

class SyntheticScene {
 public:
  explicit SyntheticScene(const core::CameraIntrinsics& intrinsics);

  // Adds a texture (CV_8UC3 or CV_8UC1) and returns its index for addRectangle(). Without `mipmaps` it is always
  // sampled at full resolution (see synth::Texture).
  int addTexture(const cv::Mat& image, bool mipmaps = true);
  // A static textured rectangle origin + a * edge_u + b * edge_v (a, b in [0, 1]); edge_u and edge_v must be
  // perpendicular. The texture spans it once, its row 0 along edge_u at the origin.
  void addRectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge_u, const Eigen::Vector3d& edge_v,
                    int texture);
  // An axis-aligned static box between two corners, every face showing `texture` once.
  void addBox(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner, int texture);
  // A mover: a rectangle that moves rigidly (see render()). Returns its id (1, 2, ...), written to
  // SyntheticView::instance.
  std::uint16_t addMovingRectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& edge_u,
                                   const Eigen::Vector3d& edge_v, int texture);
  // An axis-aligned moving box. Returns its id.
  std::uint16_t addMovingBox(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner, int texture);
  int moverCount() const { return static_cast<int>(movers_.size()); }

  // The view from T_cw with mover i + 1 moved by the rigid motion mover_motion[i] (world -> world, applied to
  // its rest geometry; missing entries: at rest).
  SyntheticView render(const core::SE3& T_cw, const std::vector<core::SE3>& mover_motion = {}) const;

  // Distance from a world point to the nearest static surface (rectangles), e.g. to check a map point.
  double distanceToStaticSurface(const Eigen::Vector3d& p_w) const;

  const core::CameraIntrinsics& intrinsics() const { return renderer_.intrinsics(); }

 private:
  synth::Renderer renderer_;
  synth::TextureBank textures_;
  synth::SceneGeometry static_;
  std::vector<synth::SceneGeometry> movers_;
};

// A closed room (4 m wide, 2.4 m high, from 1.5 m behind to 4.5 m in front of the origin) with two boxes and a
// pillar at 1.4 to 3.3 m, every surface with its own noise texture: a camera near the origin looking roughly
// along +z sees texture everywhere and depth from 1.4 to 4.5 m. `seed` draws the textures.
SyntheticScene texturedRoom(const core::CameraIntrinsics& intrinsics, std::uint32_t seed = 1);

// The dynamic front end's scene: a wall at z = 3 m, a floor at y = 0.7 m, a static crate face at z = 2 m (x in
// [0.3, 0.8], y in [-0.5, 0.2]), a static pillar at z = 1 m (x in [0.25, 0.4]) and one mover, a box face at
// z = 1.5 m (x in [-0.4, 0], y in [-0.2, 0.3]); fine noise textures (about two texels per pixel) sampled
// without mipmaps, as the front end's tests first rendered it with their own ray caster. The static part spans three planes: with a
// single static plane any fundamental matrix through its homography would also fit the box.
SyntheticScene crateScene(const core::CameraIntrinsics& intrinsics);

// A pure translation, e.g. a mover's motion for SyntheticScene::render().
core::SE3 translation(const Eigen::Vector3d& t);

// Camera paths (T_cw per frame).
// Frame i at T_wc = expSE3(i * twist_wc) * T_wc_first: a constant velocity (twist_wc = [rho, phi] per frame in the
// world frame, see core::expSE3).
std::vector<core::SE3> constantVelocityPath(int frames, const core::Vector6d& twist_wc,
                                            const core::SE3& T_wc_first = core::SE3::Identity());
// A hand-held sway from the identity: frame i at translation amplitude_m * (sin, sin, sin) and rotation
// amplitude_rad * (sin, sin, sin) about the axes, each axis with its own phase, one period over period_frames.
std::vector<core::SE3> swayPath(int frames, double amplitude_m, double amplitude_rad, double period_frames);

// A scene seen along a camera path at `fps`; frames are rendered when asked for.
class SyntheticSequence {
 public:
  // Mover motion of frame i, as for SyntheticScene::render() (empty function: movers at rest).
  using MoverMotion = std::function<std::vector<core::SE3>(int frame)>;

  SyntheticSequence(std::shared_ptr<const SyntheticScene> scene, std::vector<core::SE3> T_cw, double fps = 30,
                    MoverMotion movers = {});

  int size() const { return static_cast<int>(T_cw_.size()); }
  const core::SE3& T_cw(int i) const { return T_cw_.at(static_cast<std::size_t>(i)); }
  const std::vector<core::SE3>& path() const { return T_cw_; }
  double timestamp(int i) const { return start_timestamp_ + i / fps_; }
  const SyntheticScene& scene() const { return *scene_; }

  SyntheticView view(int i) const;
  // The frame as io::SequenceReader delivers it (index, timestamp, bgr, depth).
  io::RgbdFrame rgbdFrame(int i) const;
  static io::RgbdFrame toRgbdFrame(const SyntheticView& view, int index, double timestamp);

 private:
  std::shared_ptr<const SyntheticScene> scene_;
  std::vector<core::SE3> T_cw_;
  double fps_;
  MoverMotion movers_;
  double start_timestamp_ = 1000.0;
};

}  // namespace amos::testing
