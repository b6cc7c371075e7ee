// The public dense map's writers (include/amos/dense_map.h): the dense module's (dense/dense_map_files.h) on the
// map converted back; each checks the map's sizes first, so that a caller's inconsistent map is an error naming
// the file, not a bad file.
#include <fmt/format.h>

#include "amos/core/error.h"
#include "amos/dense_map.h"

#ifdef AMOS_HAVE_OPEN3D
#include "amos/api/dense_conversion.h"
#include "amos/dense/dense_map_files.h"
#endif

namespace amos {

namespace {

[[maybe_unused]] void requireCells(const OccupancyGrid& grid, const std::string& stem) {
  core::require(grid.rows > 0 && grid.cols > 0 &&
                    grid.cells.size() == static_cast<std::size_t>(grid.rows) * static_cast<std::size_t>(grid.cols),
                fmt::format("amos::writeFloorPlan('{}'): the grid has {} cells for {} x {}", stem, grid.cells.size(),
                            grid.rows, grid.cols));
}

[[maybe_unused]] void requireDense(const char* function) {
  core::require(denseMappingAvailable(),
                fmt::format("amos::{}: this library was built without the dense map (Open3D; install "
                            "libopen3d-dev and rebuild)", function));
}

}  // namespace

bool denseMappingAvailable() {
#ifdef AMOS_HAVE_OPEN3D
  return true;
#else
  return false;
#endif
}

void writeMeshPly(const DenseMap& map, const std::string& path) {
  requireDense("writeMeshPly");
#ifdef AMOS_HAVE_OPEN3D
  for (const auto& t : map.mesh.triangles)
    for (const std::uint32_t v : t)
      core::require(v < map.mesh.vertices.size(),
                    fmt::format("amos::writeMeshPly('{}'): a triangle names vertex {} of {}", path, v,
                                map.mesh.vertices.size()));
  dense::writeMeshPly(path, api::internalMesh(map.mesh));
#endif
}

void writeCloudPly(const DenseMap& map, const std::string& path) {
  requireDense("writeCloudPly");
#ifdef AMOS_HAVE_OPEN3D
  dense::writeCloudPly(path, api::internalCloud(map.cloud));
#endif
}

void writeFloorPlan(const DenseMap& map, const std::string& stem) {
  requireDense("writeFloorPlan");
  core::require(map.grid.has_value(),
                fmt::format("amos::writeFloorPlan('{}'): the map has no floor plan (no floor was found)", stem));
  requireCells(*map.grid, stem);
#ifdef AMOS_HAVE_OPEN3D
  const auto [grid, floor] = api::internalFloorPlan(*map.grid);
  dense::writeFloorPlan(stem + ".yaml", grid, floor);
#endif
}

}  // namespace amos
