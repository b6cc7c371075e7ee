#include "amos/dense/dense_outputs.h"

#include <fmt/format.h>

#include <filesystem>

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/PointCloudIO.h>
#include <open3d/io/TriangleMeshIO.h>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"

namespace amos::dense {

namespace fs = std::filesystem;

namespace {

// Open3D picks the format by the extension: the temporary name ends in .ply too.
template <typename Write>
void writeAtomically(const fs::path& path, Write write) {
  const fs::path partial = path.parent_path() / ("." + path.stem().string() + ".partial.ply");
  core::require(write(partial.string()), fmt::format("cannot write {}", path.string()));
  std::error_code ec;
  fs::rename(partial, path, ec);
  core::require(!ec, fmt::format("cannot write {}: {}", path.string(), ec.message()));
}

// Open3D refuses to write a cloud without points: an empty one (mode none removes nothing) is written here.
void writeEmptyCloud(const fs::path& path) {
  io::writeFileAtomically(path.string(),
                          "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty double x\n"
                          "property double y\nproperty double z\nend_header\n");
}

void writeCloud(const fs::path& path, const open3d::geometry::PointCloud& cloud) {
  if (cloud.points_.empty()) return writeEmptyCloud(path);
  writeAtomically(path, [&](const std::string& p) {
    return open3d::io::WritePointCloud(p, cloud, open3d::io::WritePointCloudOption(false, false));
  });
}

}  // namespace

const std::vector<std::string>& denseOutputNames() {
  static const std::vector<std::string> names = {"mesh.ply", "cloud.ply", "removed_points.ply", "occupancy.pgm",
                                                 "occupancy.yaml"};
  return names;
}

void writeDenseOutputs(const std::string& dir, const DenseMap& map) {
  const fs::path d(dir);
  writeAtomically(d / "mesh.ply", [&](const std::string& p) {
    return open3d::io::WriteTriangleMesh(p, *map.mesh, /*write_ascii=*/false, /*compressed=*/false,
                                         /*write_vertex_normals=*/true, /*write_vertex_colors=*/true,
                                         /*write_triangle_uvs=*/false);
  });
  writeCloud(d / "cloud.ply", *map.cloud);
  writeCloud(d / "removed_points.ply", *map.removed);
  if (map.grid && map.floor) writeOccupancyGrid(dir, "occupancy", *map.grid, *map.floor);
}

}  // namespace amos::dense
