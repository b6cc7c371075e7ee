#pragma once
// The dense map between the dense module's plain data (dense/dense_map.h) and the public one
// (include/amos/dense_map.h). Only with the dense module (AMOS_HAVE_OPEN3D).
#include "amos/dense/dense_map.h"
#include "amos/dense/dense_mapper.h"
#include "amos/dense_map.h"

namespace amos::api {

amos::DenseMap publicDenseMap(const dense::DenseMap& map);
amos::DenseSnapshot publicSnapshot(const dense::LiveCloud& live);
amos::OccupancyGrid publicGrid(const dense::OccupancyGrid& grid, const dense::FloorPlane& floor);
dense::DenseMesh internalMesh(const amos::DenseMesh& mesh);
dense::DenseCloud internalCloud(const amos::DenseCloud& cloud);
// The grid and its floor plane (what the floor plan's files need).
std::pair<dense::OccupancyGrid, dense::FloorPlane> internalFloorPlan(const amos::OccupancyGrid& grid);

}  // namespace amos::api
