#pragma once
// Furniture and props built from textured boxes, cylinders and spheres. Each builder returns geometry in its own
// frame: origin on the floor at the piece's centre, z up, front facing +x; place it with transformed(). Used by
// the room (static) and by the object movers (the pushed box, the rolling chair, the door).
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "amos/synth/random.h"
#include "amos/synth/scene.h"
#include "amos/synth/texture.h"

namespace amos::synth {

// What the builders draw with: the scene's texture bank, a random stream, optional photographs, and the texel
// size of large surfaces (props use half of it, so that small print stays legible).
struct AssetContext {
  TextureBank& textures;
  Random& rng;
  const std::vector<cv::Mat>& photos;
  double metres_per_texel = 0.004;

  Surface add(const cv::Mat& bgr, double repeat_u = 1, double repeat_v = 1);
  // Texture size in texels for a face of w x h metres at prop resolution (clamped to 16..1024).
  cv::Size texels(double width_m, double height_m) const;
  // A photograph (or an empty Mat when none were given), chosen at random.
  cv::Mat anyPhoto();
};

// Pose on the floor: position (x, y) and yaw about z (radians; the piece's +x turns to (cos yaw, sin yaw)).
Eigen::Isometry3d floorPose(double x, double y, double yaw, double z = 0);

SceneGeometry officeChair(AssetContext& ctx, std::uint16_t instance = 0);
// Desk of the given depth (x), width (y) and height; with a modesty panel under the top on its -x side.
SceneGeometry desk(AssetContext& ctx, double depth, double width, double height, bool modesty_panel);
SceneGeometry monitor(AssetContext& ctx);
SceneGeometry keyboardProp(AssetContext& ctx);
// Shelf unit whose back is at x = -depth / 2, open to +x, spanning y in [-width / 2, width / 2].
SceneGeometry bookshelf(AssetContext& ctx, double width, double height, double depth, int shelves);
SceneGeometry cardboardBox(AssetContext& ctx, const Eigen::Vector3d& size, std::uint16_t instance = 0);
SceneGeometry plant(AssetContext& ctx, double height);
SceneGeometry sofa(AssetContext& ctx, double width);
SceneGeometry cabinet(AssetContext& ctx, const Eigen::Vector3d& size);
SceneGeometry coffeeTable(AssetContext& ctx, double depth, double width, double height);
SceneGeometry mug(AssetContext& ctx);
SceneGeometry bookStack(AssetContext& ctx, int count);
// Door leaf: hinge edge on the z axis at y = 0, the leaf extends along +y by `width`, front face towards +x.
SceneGeometry doorLeaf(AssetContext& ctx, double width, double height, double thickness, std::uint16_t instance = 0);

}  // namespace amos::synth
