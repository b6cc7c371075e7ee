#include "amos/synth/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace amos::synth {

void SceneGeometry::clear() {
  quads.clear();
  cylinders.clear();
  spheres.clear();
}

void SceneGeometry::append(const SceneGeometry& other) {
  quads.insert(quads.end(), other.quads.begin(), other.quads.end());
  cylinders.insert(cylinders.end(), other.cylinders.begin(), other.cylinders.end());
  spheres.insert(spheres.end(), other.spheres.begin(), other.spheres.end());
}

void SceneGeometry::addBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size, const BoxSurfaces& faces,
                           std::uint16_t instance) {
  const double hx = size.x() / 2, hy = size.y() / 2, hz = size.z() / 2;
  using V = Eigen::Vector3d;
  // Top-left corner and right/down edges of each face as seen from outside (see Quad).
  const std::array<std::array<V, 3>, 6> local = {{
      {V(hx, -hy, hz), V(0, 2 * hy, 0), V(0, 0, -2 * hz)},   // +x
      {V(-hx, hy, hz), V(0, -2 * hy, 0), V(0, 0, -2 * hz)},  // -x
      {V(hx, hy, hz), V(-2 * hx, 0, 0), V(0, 0, -2 * hz)},   // +y
      {V(-hx, -hy, hz), V(2 * hx, 0, 0), V(0, 0, -2 * hz)},  // -y
      {V(-hx, hy, hz), V(2 * hx, 0, 0), V(0, -2 * hy, 0)},   // +z
      {V(-hx, -hy, -hz), V(2 * hx, 0, 0), V(0, 2 * hy, 0)},  // -z
  }};
  for (std::size_t f = 0; f < 6; ++f) {
    Quad q;
    q.origin = pose * local[f][0];
    q.edge_u = pose.linear() * local[f][1];
    q.edge_v = pose.linear() * local[f][2];
    q.surface = faces[f];
    q.instance = instance;
    q.cull_back = true;
    quads.push_back(q);
  }
}

void SceneGeometry::addBox(const Eigen::Vector3d& min_corner, const Eigen::Vector3d& max_corner,
                           const BoxSurfaces& faces, std::uint16_t instance) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = (min_corner + max_corner) / 2;
  addBox(pose, max_corner - min_corner, faces, instance);
}

void SceneGeometry::addCylinder(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double radius,
                                const Surface& surface, std::uint16_t instance, const Eigen::Vector3d& front_hint) {
  Cylinder c;
  const Eigen::Vector3d d = to - from;
  c.length = d.norm();
  if (c.length <= 0) return;
  c.axis = d / c.length;
  Eigen::Vector3d front = front_hint - front_hint.dot(c.axis) * c.axis;
  if (front.norm() < 1e-6) front = c.axis.unitOrthogonal();
  c.front = front.normalized();
  c.base = from;
  c.radius = radius;
  c.surface = surface;
  c.instance = instance;
  cylinders.push_back(c);
}

void SceneGeometry::addSphere(const Eigen::Vector3d& centre, double radius, const Surface& surface,
                              std::uint16_t instance, const Eigen::Vector3d& front, const Eigen::Vector3d& up) {
  Sphere s;
  s.centre = centre;
  s.radius = radius;
  s.up = up.normalized();
  Eigen::Vector3d f = front - front.dot(s.up) * s.up;
  if (f.norm() < 1e-6) f = s.up.unitOrthogonal();
  s.front = f.normalized();
  s.surface = surface;
  s.instance = instance;
  spheres.push_back(s);
}

double SceneGeometry::maxDisplacement(const SceneGeometry& o) const {
  if (quads.size() != o.quads.size() || cylinders.size() != o.cylinders.size() || spheres.size() != o.spheres.size())
    return std::numeric_limits<double>::infinity();
  double m = 0;
  for (std::size_t i = 0; i < quads.size(); ++i) {
    const Quad &a = quads[i], &b = o.quads[i];
    m = std::max({m, (a.origin - b.origin).norm(), (a.origin + a.edge_u - b.origin - b.edge_u).norm(),
                  (a.origin + a.edge_v - b.origin - b.edge_v).norm()});
  }
  for (std::size_t i = 0; i < cylinders.size(); ++i) {
    const Cylinder &a = cylinders[i], &b = o.cylinders[i];
    m = std::max({m, (a.base - b.base).norm(), (a.base + a.length * a.axis - b.base - b.length * b.axis).norm(),
                  std::abs(a.radius - b.radius)});
  }
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const Sphere &a = spheres[i], &b = o.spheres[i];
    m = std::max({m, (a.centre - b.centre).norm() + std::abs(a.radius - b.radius)});
  }
  return m;
}

SceneGeometry transformed(const SceneGeometry& g, const Eigen::Isometry3d& T) {
  SceneGeometry out = g;
  const Eigen::Matrix3d R = T.linear();
  for (Quad& q : out.quads) {
    q.origin = T * q.origin;
    q.edge_u = R * q.edge_u;
    q.edge_v = R * q.edge_v;
  }
  for (Cylinder& c : out.cylinders) {
    c.base = T * c.base;
    c.axis = R * c.axis;
    c.front = R * c.front;
  }
  for (Sphere& s : out.spheres) {
    s.centre = T * s.centre;
    s.front = R * s.front;
    s.up = R * s.up;
  }
  return out;
}

}  // namespace amos::synth
