#include "amos/synth/room.h"

#include "amos/core/error.h"
#include "amos/synth/furniture.h"
#include "amos/synth/procedural_textures.h"
#include "amos/synth/random.h"

namespace amos::synth {

using Eigen::Vector3d;

void RoomOptions::check() const {
  core::require(metres_per_texel >= 0.001 && metres_per_texel <= 0.05,
                "synth.metres_per_texel must be in [0.001, 0.05] metres");
}

namespace {

// Wall quad seen from inside the room: top-left corner, unit direction to the right, length.
Quad wallQuad(const Vector3d& top_left, const Vector3d& right, double length, double height, int texture) {
  Quad q;
  q.origin = top_left;
  q.edge_u = right * length;
  q.edge_v = Vector3d(0, 0, -height);
  q.surface.texture = texture;
  return q;
}

void place(SceneGeometry& room, const SceneGeometry& piece, const Eigen::Isometry3d& pose) {
  room.append(transformed(piece, pose));
}

}  // namespace

Room buildRoom(const RoomOptions& options, std::uint32_t seed, TextureBank& textures,
               const std::vector<cv::Mat>& photos) {
  options.check();
  Room room;
  const RoomLayout& L = room.layout;
  const double X = L.half_extent.x(), Y = L.half_extent.y(), H = L.height;
  const double mpt = options.metres_per_texel;
  Random rng(deriveSeed(seed, Stream::kRoom));
  AssetContext ctx{textures, rng, photos, mpt};
  SceneGeometry& g = room.geometry;
  using textures::WallFeature;
  using Type = WallFeature::Type;

  // Walls, with fixed features in each wall's own coordinates (metres from its top-left seen from inside).
  // Walls overlap the floor and ceiling by a centimetre so that no ray slips through a seam.
  const double e = 0.01;
  auto addWall = [&](const Vector3d& top_left, const Vector3d& right, double length, int style,
                     std::vector<WallFeature> features) {
    textures::WallSpec spec;
    spec.length_m = length;
    spec.height_m = H;
    spec.metres_per_texel = mpt;
    spec.style = style;
    spec.features = std::move(features);
    const int tex = textures.add(Texture(textures::wall(spec, rng, photos)));
    g.quads.push_back(wallQuad(top_left + Vector3d(0, 0, e) - right * e, right, length + 2 * e, H + 2 * e, tex));
  };
  const int styles[4] = {rng.uniformInt(0, 1), rng.uniformInt(0, 3), rng.uniformInt(0, 3), rng.uniformInt(0, 3)};
  // East wall (x = +X), behind the desk; seen from inside its left end is y = +Y. Door at y in [hinge, hinge+w].
  addWall({X, Y, H}, {0, -1, 0}, 2 * Y, styles[0],
          {{Type::kDoorway,
            cv::Rect2d(Y - L.door_hinge_y - L.door_width, H - L.door_height, L.door_width, L.door_height)}});
  // North wall (y = +Y): a whiteboard.
  addWall({-X, Y, H}, {1, 0, 0}, 2 * X, styles[1], {{Type::kWhiteboard, cv::Rect2d(2.4, 0.75, 1.8, 1.0)}});
  // West wall (x = -X): a window above the sofa.
  addWall({-X, -Y, H}, {0, 1, 0}, 2 * Y, styles[2], {{Type::kWindow, cv::Rect2d(Y - 1.0, 0.55, 2.0, 1.1)}});
  // South wall (y = -Y).
  addWall({X, -Y, H}, {-1, 0, 0}, 2 * X, styles[3], {});

  // Floor (texture origin at (-X, +Y), u along +x, v along -y) with a rug in front of the desk; ceiling.
  {
    Quad f;
    f.origin = Vector3d(-X - e, Y + e, 0);
    f.edge_u = Vector3d(2 * X + 2 * e, 0, 0);
    f.edge_v = Vector3d(0, -2 * Y - 2 * e, 0);
    f.surface.texture = textures.add(Texture(
        textures::floorPlanks(2 * X + 2 * e, 2 * Y + 2 * e, mpt, cv::Point2d(X + 0.2, Y), cv::Size2d(2.4, 1.8), rng)));
    g.quads.push_back(f);
    Quad c;
    c.origin = Vector3d(-X - e, -Y - e, H);
    c.edge_u = Vector3d(2 * X + 2 * e, 0, 0);
    c.edge_v = Vector3d(0, 2 * Y + 2 * e, 0);
    c.surface.texture = textures.add(Texture(textures::ceiling(2 * X + 2 * e, 2 * Y + 2 * e, 2 * mpt, rng)));
    g.quads.push_back(c);
  }

  // Main desk facing the camera stage: one monitor in the middle (so that it hides neither seat), keyboards
  // in front of the seats, books and a mug.
  const double dx = L.desk_centre.x(), dy = L.desk_centre.y(), top = L.desk_height;
  place(g, desk(ctx, L.desk_size.x(), L.desk_size.y(), top, true), floorPose(dx, dy, 0));
  place(g, monitor(ctx), floorPose(dx + 0.15, dy, M_PI, top));
  for (const Eigen::Vector2d& s : L.seats) place(g, keyboardProp(ctx), floorPose(dx + 0.22, s.y(), 0, top));
  place(g, bookStack(ctx, 4), floorPose(dx - 0.2, dy - 0.62, 0.2, top));
  place(g, bookStack(ctx, 2), floorPose(dx - 0.15, dy + 0.45, -0.3, top));
  place(g, mug(ctx), floorPose(dx - 0.25, dy + 0.72, 0, top));
  for (const Eigen::Vector2d& s : L.seats)
    place(g, officeChair(ctx), floorPose(s.x(), s.y(), M_PI + rng.uniform(-0.2, 0.2)));

  // Against the east wall: bookshelf and a filing cabinet; boxes stacked near the shelf.
  place(g, bookshelf(ctx, 1.2, 1.9, 0.35, 5), floorPose(X - 0.175, -2.1, M_PI));
  place(g, cabinet(ctx, {0.45, 0.5, 1.1}), floorPose(X - 0.225, -1.2, M_PI));
  place(g, cardboardBox(ctx, {0.5, 0.45, 0.4}), floorPose(2.3, -2.55, 0.1));
  place(g, cardboardBox(ctx, {0.45, 0.4, 0.35}), floorPose(2.32, -2.55, -0.15, 0.401));
  place(g, cardboardBox(ctx, {0.6, 0.5, 0.45}), floorPose(1.6, -2.6, 0.05));
  if (!options.door_is_mover) {
    // Closed door leaf, a centimetre proud of the wall, facing into the room (-x).
    place(g, doorLeaf(ctx, L.door_width, L.door_height, 0.04),
          floorPose(X - 0.03, L.door_hinge_y + L.door_width, M_PI));
  }

  // North wall: bookcase and a plant; south wall: a second desk with a monitor and a chair, boxes.
  place(g, bookshelf(ctx, 1.4, 1.8, 0.32, 5), floorPose(1.7, Y - 0.16, -M_PI / 2));
  place(g, plant(ctx, 1.1), floorPose(0.6, Y - 0.3, 0));
  place(g, cardboardBox(ctx, {0.4, 0.4, 0.3}), floorPose(-0.4, Y - 0.3, 0.3));
  place(g, desk(ctx, 0.7, 1.6, 0.74, false), floorPose(-2.0, -Y + 0.35, M_PI / 2));
  place(g, monitor(ctx), floorPose(-2.0, -Y + 0.3, M_PI / 2, 0.74));
  place(g, bookStack(ctx, 3), floorPose(-2.55, -Y + 0.35, 0.4, 0.74));
  place(g, officeChair(ctx), floorPose(-2.0, -Y + 1.05, -M_PI / 2 + 0.3));
  place(g, cardboardBox(ctx, {0.5, 0.4, 0.4}), floorPose(-0.6, -Y + 0.3, -0.2));
  place(g, plant(ctx, 1.2), floorPose(-X + 0.35, -Y + 0.35, 0));

  // West wall: sofa under the window, coffee table with books, a plant in the corner.
  place(g, sofa(ctx, 2.0), floorPose(-X + 0.45, 0, 0));
  place(g, coffeeTable(ctx, 0.5, 1.0, 0.42), floorPose(-2.3, 0, 0));
  place(g, bookStack(ctx, 2), floorPose(-2.3, 0.2, 0.5, 0.42));
  place(g, plant(ctx, 1.0), floorPose(-X + 0.35, Y - 0.35, 0));

  // Ceiling lights (world-fixed, so static surfaces keep their shading from every viewpoint).
  room.lighting.ambient = 0.5;
  for (const Vector3d& p : {Vector3d(-1.8, -1.5, H - 0.1), Vector3d(-1.8, 1.5, H - 0.1), Vector3d(1.8, -1.5, H - 0.1),
                            Vector3d(1.8, 1.5, H - 0.1), Vector3d(0, 0, H - 0.1)})
    room.lighting.lights.push_back({p, 0.22, 2.5});
  return room;
}

}  // namespace amos::synth
