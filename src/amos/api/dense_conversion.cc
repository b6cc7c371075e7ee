// Only with the dense module (the library without it has no dense map to convert).
#ifdef AMOS_HAVE_OPEN3D
#include "amos/api/dense_conversion.h"

namespace amos::api {

namespace {

amos::DenseCloud publicCloud(const dense::DenseCloud& cloud) { return {cloud.points, cloud.normals, cloud.colours}; }

}  // namespace

amos::OccupancyGrid publicGrid(const dense::OccupancyGrid& grid, const dense::FloorPlane& floor) {
  amos::OccupancyGrid g;
  g.rows = grid.height;
  g.cols = grid.width;
  g.cells = grid.cells;
  g.resolution = grid.resolution;
  g.origin = grid.origin;
  g.T_mw = grid.T_mw.matrix();
  g.floor_normal = floor.normal;
  g.floor_offset = floor.offset;
  return g;
}

amos::DenseMap publicDenseMap(const dense::DenseMap& map) {
  amos::DenseMap out;
  out.mesh = {map.mesh.vertices, map.mesh.normals, map.mesh.colours, map.mesh.triangles};
  out.cloud = publicCloud(map.cloud);
  out.removed = publicCloud(map.removed);
  if (map.grid && map.floor) out.grid = publicGrid(*map.grid, *map.floor);
  if (map.stats.contains("frames_fused")) out.frames_fused = map.stats["frames_fused"].get<std::size_t>();
  return out;
}

amos::DenseSnapshot publicSnapshot(const dense::LiveCloud& live) {
  amos::DenseSnapshot s;
  s.cloud.points.reserve(live.points.size());
  for (const Eigen::Vector3f& p : live.points) s.cloud.points.push_back(p.cast<double>());
  s.cloud.colours = live.colours;
  s.frames_fused = live.frames_fused;
  return s;
}

dense::DenseMesh internalMesh(const amos::DenseMesh& mesh) {
  return {mesh.vertices, mesh.normals, mesh.colours, mesh.triangles};
}

dense::DenseCloud internalCloud(const amos::DenseCloud& cloud) { return {cloud.points, cloud.normals, cloud.colours}; }

std::pair<dense::OccupancyGrid, dense::FloorPlane> internalFloorPlan(const amos::OccupancyGrid& grid) {
  dense::OccupancyGrid g;
  g.width = grid.cols;
  g.height = grid.rows;
  g.cells = grid.cells;
  g.resolution = grid.resolution;
  g.origin = grid.origin;
  g.T_mw = core::SE3(grid.T_mw);
  dense::FloorPlane floor;
  floor.normal = grid.floor_normal;
  floor.offset = grid.floor_offset;
  return {g, floor};
}

}  // namespace amos::api

#endif  // AMOS_HAVE_OPEN3D
