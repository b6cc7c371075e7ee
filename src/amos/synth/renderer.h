#pragma once
// A small z-buffered renderer for the synthetic scenes: each primitive is rasterised over the screen region its
// projection covers, and every candidate pixel is decided by an exact ray intersection through the pixel centre
// (pixel (x, y) looks along ((x - cx) / fx, (y - cy) / fy, 1), as core::PinholeCamera::backProject). Depth is
// therefore exact to float precision, and the instance mask is exactly where each mover's geometry is visible.
// Shading is deferred: one trilinear texture lookup and Lambertian lighting from world-fixed lights per pixel,
// so a static surface keeps its colour from every viewpoint.
#include <opencv2/core.hpp>
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/synth/scene.h"
#include "amos/synth/texture.h"

namespace amos::synth {

struct PointLight {
  Eigen::Vector3d position_w = Eigen::Vector3d::Zero();
  double intensity = 0.3;  // added to the ambient term for a surface facing the light at distance 0
  double falloff_m = 3.0;  // distance at which the light has dropped to half
};

struct Lighting {
  double ambient = 0.55;
  std::vector<PointLight> lights;
};

struct RenderOptions {
  double near_m = 0.05;  // nothing closer than this along the optical axis is drawn
  void check() const;
};

// Image rows [begin, end) (end < 0: to the last row); a renderer given a band renders only those rows.
struct RowBand {
  int begin = 0;
  int end = -1;
};

struct RenderedImage {
  cv::Mat color;      // CV_32FC3, B G R in 0..255 (not clamped); empty when not asked for
  cv::Mat depth;      // CV_32F, z along the optical axis in metres; 0 where no surface was hit
  cv::Mat instance;   // CV_16U, instance id of the visible primitive (0 = static scene)
  cv::Mat incidence;  // CV_32F, |cos| of the angle between the viewing ray and the surface normal
};

class Renderer {
 public:
  explicit Renderer(const core::CameraIntrinsics& intrinsics, const RenderOptions& options = {});

  // Renders the union of `parts` seen from the camera pose T_cw. Textures are needed only with `with_color`.
  // With a band, only its rows are rendered and the images hold just them (their row 0 is image row
  // band.begin), each pixel exactly as in the whole image: a rolling shutter renders the image band by band.
  RenderedImage render(const std::vector<const SceneGeometry*>& parts, const TextureBank& textures,
                       const Lighting& lighting, const core::SE3& T_cw, bool with_color = true,
                       const RowBand& band = {}) const;

  const core::CameraIntrinsics& intrinsics() const { return intr_; }

 private:
  core::CameraIntrinsics intr_;
  RenderOptions options_;
  std::vector<double> ray_x_, ray_y_;  // per column / row: (x - cx) / fx and (y - cy) / fy
};

}  // namespace amos::synth
