#include "amos/dense/open3d_geometry.h"

#include <algorithm>
#include <cmath>

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

namespace amos::dense {
namespace {

Rgb bytesOf(const Eigen::Vector3d& c) {
  Rgb out;
  for (int i = 0; i < 3; ++i) out[i] = static_cast<std::uint8_t>(std::round(std::clamp(c[i], 0.0, 1.0) * 255.0));
  return out;
}

std::vector<Rgb> bytesOf(const std::vector<Eigen::Vector3d>& colours) {
  std::vector<Rgb> out;
  out.reserve(colours.size());
  for (const auto& c : colours) out.push_back(bytesOf(c));
  return out;
}

std::vector<Eigen::Vector3d> unitOf(const std::vector<Rgb>& colours) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(colours.size());
  for (const Rgb& c : colours) out.emplace_back(c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
  return out;
}

}  // namespace

DenseMesh plainMesh(const open3d::geometry::TriangleMesh& mesh) {
  DenseMesh out;
  out.vertices = mesh.vertices_;
  out.normals = mesh.vertex_normals_;
  out.colours = bytesOf(mesh.vertex_colors_);
  out.triangles.reserve(mesh.triangles_.size());
  for (const Eigen::Vector3i& t : mesh.triangles_) {
    out.triangles.push_back(
        {static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]), static_cast<std::uint32_t>(t[2])});
  }
  return out;
}

DenseCloud plainCloud(const open3d::geometry::PointCloud& cloud) {
  return {cloud.points_, cloud.normals_, bytesOf(cloud.colors_)};
}

open3d::geometry::PointCloud open3dCloud(const DenseCloud& cloud) {
  open3d::geometry::PointCloud out;
  out.points_ = cloud.points;
  out.normals_ = cloud.normals;
  out.colors_ = unitOf(cloud.colours);
  return out;
}

}  // namespace amos::dense
