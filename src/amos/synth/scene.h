#pragma once
// Scene geometry in world coordinates (metres, z up, floor at z = 0): textured quads (planes, box faces,
// billboards), capped cylinders and spheres. Every primitive carries the instance id written to the mask
// (0 = static scene). Geometry is plain data: movers build theirs anew for each instant.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace amos::synth {

// How a primitive looks: a texture of the scene's TextureBank, repeated `repeat_u` x `repeat_v` times across it,
// multiplied by `tint`.
struct Surface {
  int texture = -1;
  double repeat_u = 1, repeat_v = 1;
  cv::Vec3f tint{1, 1, 1};
  bool alpha_test = false;  // cut-outs: where the texture's alpha is below 0.5 there is no surface at all
};

// Parallelogram origin + a * edge_u + b * edge_v, a, b in [0, 1]; texture (s, t) = (a, b) * repeat. Put the
// origin at the top-left corner as seen from the front, edge_u to the right and edge_v downwards, so images
// appear upright. Two-sided.
struct Quad {
  Eigen::Vector3d origin, edge_u, edge_v;
  Surface surface;
  std::uint16_t instance = 0;
  // Faces of closed solids are seen from the front only (front normal = edge_v x edge_u); skipping their backs
  // saves work and changes nothing, since the solid's front faces hide them.
  bool cull_back = false;
};

// Cylinder from `base` along unit `axis` over `length`; texture s goes around (s = 0.5 at `front`, a unit vector
// perpendicular to the axis), t along the axis from the far end (t = 0 at base + length * axis).
struct Cylinder {
  Eigen::Vector3d base, axis, front;
  double radius = 0, length = 0;
  bool capped = true;
  Surface surface;
  std::uint16_t instance = 0;
};

// Sphere; texture s = longitude (s = 0.5 at `front`), t = colatitude from `up` (t = 0 at the top).
struct Sphere {
  Eigen::Vector3d centre, front, up;
  double radius = 0;
  Surface surface;
  std::uint16_t instance = 0;
};

// Box faces in the order +x, -x, +y, -y, +z (top), -z (bottom) of the box's own frame.
using BoxSurfaces = std::array<Surface, 6>;
inline BoxSurfaces allFaces(const Surface& s) { return {s, s, s, s, s, s}; }

struct SceneGeometry {
  std::vector<Quad> quads;
  std::vector<Cylinder> cylinders;
  std::vector<Sphere> spheres;

  void clear();
  std::size_t size() const { return quads.size() + cylinders.size() + spheres.size(); }
  void append(const SceneGeometry& other);

  // Box of full extents `size` whose centre and orientation are `pose` (box frame -> world). Each face's
  // texture is upright when the box's local z is up.
  void addBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size, const BoxSurfaces& faces,
              std::uint16_t instance = 0);
  // Axis-aligned box between two corners.
  void addBox(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner, const BoxSurfaces& faces,
              std::uint16_t instance = 0);
  // Cylinder between two points.
  void addCylinder(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double radius, const Surface& surface,
                   std::uint16_t instance = 0, const Eigen::Vector3d& front_hint = Eigen::Vector3d::UnitX());
  void addSphere(const Eigen::Vector3d& centre, double radius, const Surface& surface, std::uint16_t instance = 0,
                 const Eigen::Vector3d& front = Eigen::Vector3d::UnitX(),
                 const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

  // Largest distance between corresponding defining points of two geometries with the same structure (how far
  // anything moved between two instants); +infinity when the structures differ.
  double maxDisplacement(const SceneGeometry& other) const;
};

// Rigid transform applied to every primitive of a geometry (for movers built in their own frame).
SceneGeometry transformed(const SceneGeometry& geometry, const Eigen::Isometry3d& T);

}  // namespace amos::synth
