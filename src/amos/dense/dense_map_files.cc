#include "amos/dense/dense_map_files.h"

#include <fmt/format.h>

#include <cstring>
#include <type_traits>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"
#include "amos/io/occupancy_grid_file.h"

namespace amos::dense {

namespace {

static_assert(sizeof(double) == 8 && sizeof(std::uint32_t) == 4, "PLY's double and uint");

// Binary little-endian PLY, built in memory and written by io::writeFileAtomically, which checks every write: a
// full disk is an error and leaves nothing under the final name (Open3D's writer reported success for a file cut
// short). The layout is the one Open3D writes and reads: vertices as doubles, normals when there are any, colours
// as bytes, faces as a byte count and unsigned 32-bit indices.
class PlyBytes {
 public:
  template <typename T>
  void put(T value) {
    static_assert(std::is_arithmetic_v<T>);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));  // little-endian machines only (x86-64, arm64)
    out_.append(bytes, sizeof(T));
  }
  void putVector(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) put(v[i]);
  }
  void putColour(const Rgb& c) { out_.append(reinterpret_cast<const char*>(c.data()), 3); }
  std::string& text() { return out_; }

 private:
  std::string out_;
};

std::string vertexHeader(std::size_t count, bool normals, bool colours) {
  std::string h = fmt::format(
      "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty double x\n"
      "property double y\nproperty double z\n",
      count);
  if (normals) h += "property double nx\nproperty double ny\nproperty double nz\n";
  if (colours) h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  return h;
}

void requireSizes(const std::string& path, std::size_t points, std::size_t normals, std::size_t colours) {
  core::require(normals == 0 || normals == points,
                fmt::format("cannot write {}: {} normals for {} points", path, normals, points));
  core::require(colours == 0 || colours == points,
                fmt::format("cannot write {}: {} colours for {} points", path, colours, points));
}

void putVertices(PlyBytes& ply, const std::vector<Eigen::Vector3d>& points,
                 const std::vector<Eigen::Vector3d>& normals, const std::vector<Rgb>& colours) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    ply.putVector(points[i]);
    if (!normals.empty()) ply.putVector(normals[i]);
    if (!colours.empty()) ply.putColour(colours[i]);
  }
}

}  // namespace

void writeMeshPly(const std::string& path, const DenseMesh& mesh) {
  requireSizes(path, mesh.vertices.size(), mesh.normals.size(), mesh.colours.size());
  PlyBytes ply;
  ply.text() = vertexHeader(mesh.vertices.size(), !mesh.normals.empty(), !mesh.colours.empty()) +
               fmt::format("element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
                           mesh.triangles.size());
  putVertices(ply, mesh.vertices, mesh.normals, mesh.colours);
  for (const auto& t : mesh.triangles) {
    core::require(t[0] < mesh.vertices.size() && t[1] < mesh.vertices.size() && t[2] < mesh.vertices.size(),
                  fmt::format("cannot write {}: a triangle names a vertex beyond the {}", path, mesh.vertices.size()));
    ply.put(std::uint8_t{3});
    for (const std::uint32_t index : t) ply.put(index);
  }
  io::writeFileAtomically(path, ply.text());
}

void writeCloudPly(const std::string& path, const DenseCloud& cloud) {
  requireSizes(path, cloud.points.size(), cloud.normals.size(), cloud.colours.size());
  PlyBytes ply;
  ply.text() = vertexHeader(cloud.points.size(), !cloud.normals.empty(), !cloud.colours.empty()) + "end_header\n";
  putVertices(ply, cloud.points, cloud.normals, cloud.colours);
  io::writeFileAtomically(path, ply.text());
}

void writeFloorPlan(const std::string& yaml_path, const OccupancyGrid& grid, const FloorPlane& floor) {
  io::OccupancyGridFile file;
  file.width = grid.width;
  file.height = grid.height;
  file.cells = grid.cells;
  file.resolution = grid.resolution;
  file.origin = {grid.origin.x(), grid.origin.y(), 0.0};
  const Eigen::Matrix4d T = grid.T_mw.matrix();
  io::writeOccupancyGridFile(
      yaml_path, file,
      {"ROS map_server / Nav2 map: the floor plan of the dense static map (amos-slam run --dense).",
       "Map frame: on the floor, z up. World (the trajectory's frame) -> map, row-major 4x4 (p_map = T_mw p_w):",
       fmt::format("  T_mw: [{}]", fmt::join(T.data(), T.data() + 16, ", ")),
       fmt::format("Floor plane in the world: normal . p + offset = 0, normal [{:.6f}, {:.6f}, {:.6f}], offset {:.6f}",
                   floor.normal.x(), floor.normal.y(), floor.normal.z(), floor.offset)});
}

}  // namespace amos::dense
