#include "amos/synth/furniture.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "amos/synth/procedural_textures.h"

namespace amos::synth {

using Eigen::Vector3d;

Surface AssetContext::add(const cv::Mat& bgr, double repeat_u, double repeat_v) {
  Surface s;
  s.texture = textures.add(Texture(bgr));
  s.repeat_u = repeat_u;
  s.repeat_v = repeat_v;
  return s;
}

cv::Size AssetContext::texels(double width_m, double height_m) const {
  const double m = metres_per_texel / 2;
  return {std::clamp(static_cast<int>(width_m / m), 16, 1024), std::clamp(static_cast<int>(height_m / m), 16, 1024)};
}

cv::Mat AssetContext::anyPhoto() {
  if (photos.empty()) return cv::Mat();
  return photos[static_cast<std::size_t>(rng.uniformInt(0, static_cast<int>(photos.size()) - 1))];
}

Eigen::Isometry3d floorPose(double x, double y, double yaw, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Vector3d(x, y, z);
  return T;
}

namespace {
Eigen::Isometry3d at(const Vector3d& centre, double yaw = 0) {
  return floorPose(centre.x(), centre.y(), yaw, centre.z());
}
}  // namespace

SceneGeometry officeChair(AssetContext& ctx, std::uint16_t instance) {
  SceneGeometry g;
  const Surface cloth =
      ctx.add(textures::fabric(ctx.texels(0.5, 0.5), textures::randomColour(ctx.rng, 0.2, 0.7, 0.15, 0.45), ctx.rng));
  const Surface steel = ctx.add(textures::metal(cv::Size(64, 64), cv::Scalar(60, 60, 65), ctx.rng));
  g.addBox(at({0, 0, 0.47}), {0.46, 0.46, 0.07}, allFaces(cloth), instance);
  g.addBox(at({-0.22, 0, 0.82}), {0.06, 0.44, 0.5}, allFaces(cloth), instance);
  g.addBox(at({-0.2, 0, 0.56}), {0.03, 0.06, 0.12}, allFaces(steel), instance);
  for (double side : {-1.0, 1.0}) {
    g.addBox(at({0.0, side * 0.24, 0.64}), {0.3, 0.05, 0.03}, allFaces(steel), instance);
    g.addBox(at({0.0, side * 0.24, 0.55}), {0.03, 0.03, 0.16}, allFaces(steel), instance);
  }
  g.addCylinder({0, 0, 0.08}, {0, 0, 0.44}, 0.025, steel, instance);
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * M_PI * k / 5 + 0.3;
    g.addBox(floorPose(0.14 * std::cos(a), 0.14 * std::sin(a), a, 0.07), {0.3, 0.04, 0.03}, allFaces(steel), instance);
    g.addSphere({0.28 * std::cos(a), 0.28 * std::sin(a), 0.03}, 0.03, steel, instance);
  }
  return g;
}

SceneGeometry desk(AssetContext& ctx, double depth, double width, double height, bool modesty_panel) {
  SceneGeometry g;
  const Surface top = ctx.add(textures::deskTop(ctx.texels(width, depth), ctx.rng));
  const Surface edge = ctx.add(textures::wood(cv::Size(256, 16), 0.2, ctx.rng));
  const Surface steel = ctx.add(textures::metal(cv::Size(32, 128), cv::Scalar(150, 150, 155), ctx.rng));
  // The +z face's texture u runs along the box's x; the desk's long side is y, so the top is a rotated box.
  g.addBox(floorPose(0, 0, M_PI / 2, height - 0.015), {width, depth, 0.03},
           BoxSurfaces{edge, edge, edge, edge, top, edge});
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      g.addBox(at({sx * (depth / 2 - 0.05), sy * (width / 2 - 0.05), (height - 0.03) / 2}), {0.05, 0.05, height - 0.03},
               allFaces(steel));
  if (modesty_panel) {
    const Surface panel = ctx.add(textures::wood(ctx.texels(width, 0.45), 0.35, ctx.rng));
    g.addBox(at({-depth / 2 + 0.07, 0, height - 0.3}), {0.02, width - 0.14, 0.45}, allFaces(panel));
  }
  return g;
}

SceneGeometry monitor(AssetContext& ctx) {
  SceneGeometry g;
  const Surface screen =
      ctx.add(textures::screen(ctx.texels(0.56, 0.34), ctx.rng, ctx.rng.chance(0.5) ? ctx.anyPhoto() : cv::Mat()));
  const Surface plastic = ctx.add(textures::metal(cv::Size(64, 64), cv::Scalar(30, 30, 32), ctx.rng));
  g.addBox(at({0, 0, 0.27}), {0.04, 0.56, 0.34}, BoxSurfaces{screen, plastic, plastic, plastic, plastic, plastic});
  g.addBox(at({-0.04, 0, 0.07}), {0.03, 0.06, 0.14}, allFaces(plastic));
  g.addBox(at({-0.02, 0, 0.008}), {0.18, 0.24, 0.016}, allFaces(plastic));
  return g;
}

SceneGeometry keyboardProp(AssetContext& ctx) {
  SceneGeometry g;
  const Surface keys = ctx.add(textures::keyboard(ctx.texels(0.45, 0.15), ctx.rng));
  const Surface plastic = ctx.add(textures::metal(cv::Size(32, 32), cv::Scalar(45, 45, 48), ctx.rng));
  g.addBox(floorPose(0, 0, -M_PI / 2, 0.012), {0.45, 0.15, 0.024},
           BoxSurfaces{plastic, plastic, plastic, plastic, keys, plastic});
  return g;
}

SceneGeometry bookshelf(AssetContext& ctx, double width, double height, double depth, int shelves) {
  SceneGeometry g;
  const Surface board = ctx.add(textures::wood(ctx.texels(depth, width), ctx.rng.uniform(0.1, 0.7), ctx.rng));
  const double t = 0.02;
  for (double side : {-1.0, 1.0})
    g.addBox(at({0, side * (width / 2 - t / 2), height / 2}), {depth, t, height}, allFaces(board));
  g.addBox(at({-depth / 2 + t / 2, 0, height / 2}), {t, width - 2 * t, height}, allFaces(board));
  const double gap = (height - t) / shelves;
  for (int i = 0; i <= shelves; ++i) g.addBox(at({0, 0, t / 2 + i * gap}), {depth, width - 2 * t, t}, allFaces(board));
  for (int i = 0; i < shelves; ++i) {
    const double book_h = gap * ctx.rng.uniform(0.75, 0.9);
    const Surface spines = ctx.add(textures::books(ctx.texels(width - 2 * t, book_h), ctx.rng));
    const Surface dark = ctx.add(textures::metal(cv::Size(32, 32), cv::Scalar(40, 45, 55), ctx.rng));
    g.addBox(at({-0.02, 0, t + i * gap + book_h / 2}), {depth * 0.8, width - 2 * t - 0.01, book_h},
             BoxSurfaces{spines, dark, dark, dark, dark, dark});
  }
  return g;
}

SceneGeometry cardboardBox(AssetContext& ctx, const Vector3d& size, std::uint16_t instance) {
  SceneGeometry g;
  const Surface a = ctx.add(textures::cardboard(ctx.texels(size.y(), size.z()), ctx.rng));
  const Surface b = ctx.add(textures::cardboard(ctx.texels(size.x(), size.z()), ctx.rng));
  const Surface top = ctx.add(textures::cardboard(ctx.texels(size.x(), size.y()), ctx.rng));
  g.addBox(at({0, 0, size.z() / 2 + 0.001}), size, BoxSurfaces{a, a, b, b, top, top}, instance);
  return g;
}

SceneGeometry plant(AssetContext& ctx, double height) {
  SceneGeometry g;
  const Surface pot = ctx.add(textures::metal(cv::Size(128, 64), cv::Scalar(60, 90, 170), ctx.rng));
  const Surface leaf = ctx.add(textures::leaves(cv::Size(512, 256), ctx.rng));
  const double s = height;  // a 1 m plant: 30 cm pot, foliage of 25 cm radius
  const double pot_h = 0.3 * s;
  g.addCylinder({0, 0, 0}, {0, 0, pot_h}, 0.14 * s, pot);
  g.addSphere({0, 0, pot_h + 0.22 * s}, 0.25 * s, leaf);
  g.addSphere({0.08 * s, 0.05 * s, height - 0.18 * s}, 0.18 * s, leaf);
  return g;
}

SceneGeometry sofa(AssetContext& ctx, double width) {
  SceneGeometry g;
  const Surface cloth =
      ctx.add(textures::fabric(ctx.texels(width, 0.5), textures::randomColour(ctx.rng, 0.3, 0.8, 0.3, 0.7), ctx.rng));
  g.addBox(at({0.05, 0, 0.22}), {0.8, width, 0.44}, allFaces(cloth));
  g.addBox(at({-0.3, 0, 0.6}), {0.2, width, 0.5}, allFaces(cloth));
  for (double side : {-1.0, 1.0})
    g.addBox(at({0.05, side * (width / 2 - 0.1), 0.32}), {0.8, 0.2, 0.64}, allFaces(cloth));
  // Two cushions with a print.
  for (double side : {-1.0, 1.0}) {
    const Surface cushion = ctx.add(textures::poster(cv::Size(128, 128), ctx.rng));
    g.addBox(at({-0.12, side * width / 4, 0.6}), {0.1, 0.4, 0.36}, allFaces(cushion));
  }
  return g;
}

SceneGeometry cabinet(AssetContext& ctx, const Vector3d& size) {
  SceneGeometry g;
  cv::Mat front = textures::metal(ctx.texels(size.y(), size.z()), cv::Scalar(170, 160, 150), ctx.rng);
  const int drawers = 3;
  for (int i = 0; i < drawers; ++i) {
    const int h = front.rows / drawers;
    cv::rectangle(front, cv::Rect(6, i * h + 4, front.cols - 12, h - 8), cv::Scalar(90, 85, 80), 3);
    cv::rectangle(front, cv::Rect(front.cols / 2 - front.cols / 8, i * h + h / 5, front.cols / 4, h / 12 + 2),
                  cv::Scalar(50, 50, 50), cv::FILLED);
    cv::rectangle(front, cv::Rect(front.cols / 2 - front.cols / 10, i * h + h / 3, front.cols / 5, h / 6),
                  cv::Scalar(240, 240, 240), cv::FILLED);
    cv::putText(front, std::string(1, static_cast<char>('A' + ctx.rng.uniformInt(0, 25))) + std::to_string(i + 1),
                cv::Point(front.cols / 2 - front.cols / 14, i * h + h / 3 + h / 7), cv::FONT_HERSHEY_SIMPLEX, h / 120.0,
                cv::Scalar(20, 20, 20), 2, cv::LINE_AA);
  }
  const Surface f = ctx.add(front);
  const Surface side = ctx.add(textures::metal(cv::Size(64, 64), cv::Scalar(170, 160, 150), ctx.rng));
  g.addBox(at({0, 0, size.z() / 2}), size, BoxSurfaces{f, side, side, side, side, side});
  return g;
}

SceneGeometry coffeeTable(AssetContext& ctx, double depth, double width, double height) {
  SceneGeometry g;
  const Surface top = ctx.add(textures::deskTop(ctx.texels(width, depth), ctx.rng));
  const Surface leg = ctx.add(textures::wood(cv::Size(32, 64), 0.7, ctx.rng));
  g.addBox(floorPose(0, 0, M_PI / 2, height - 0.02), {width, depth, 0.04}, BoxSurfaces{leg, leg, leg, leg, top, leg});
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      g.addBox(at({sx * (depth / 2 - 0.04), sy * (width / 2 - 0.04), (height - 0.04) / 2}), {0.04, 0.04, height - 0.04},
               allFaces(leg));
  return g;
}

SceneGeometry mug(AssetContext& ctx) {
  SceneGeometry g;
  const Surface s = ctx.add(textures::poster(cv::Size(128, 64), ctx.rng));
  g.addCylinder({0, 0, 0}, {0, 0, 0.1}, 0.04, s, 0, Vector3d::UnitX());
  return g;
}

SceneGeometry bookStack(AssetContext& ctx, int count) {
  SceneGeometry g;
  double z = 0;
  for (int i = 0; i < count; ++i) {
    const double h = ctx.rng.uniform(0.02, 0.05);
    const Surface cover = ctx.add(textures::poster(ctx.texels(0.22, 0.3), ctx.rng));
    const Surface pages = ctx.add(textures::books(cv::Size(128, 32), ctx.rng));
    g.addBox(floorPose(0, 0, ctx.rng.uniform(-0.3, 0.3), z + h / 2), {0.22, 0.3, h},
             BoxSurfaces{pages, pages, pages, pages, cover, cover});
    z += h;
  }
  return g;
}

SceneGeometry doorLeaf(AssetContext& ctx, double width, double height, double thickness, std::uint16_t instance) {
  SceneGeometry g;
  const Surface front = ctx.add(textures::door(ctx.texels(width, height), ctx.rng));
  const Surface edge = ctx.add(textures::wood(cv::Size(16, 128), 0.4, ctx.rng));
  // Seen from +x the texture's right side (where the handle is drawn) is +y: the free edge.
  g.addBox(at({0, width / 2, height / 2}), {thickness, width, height},
           BoxSurfaces{front, front, edge, edge, edge, edge}, instance);
  return g;
}

}  // namespace amos::synth
