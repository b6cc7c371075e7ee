#pragma once
// The dense map's files, from its plain data (dense_map.h), each written under a temporary name and renamed (a
// killed run or a full disk never leaves half a file under the final name), each on its own (one that cannot be
// written leaves the others to be written):
//   mesh PLY    coloured triangle mesh, binary, with vertex normals (run --dense: mesh.ply)
//   cloud PLY   points, coloured, with normals when the cloud has them, binary (cloud.ply, removed_points.ply); a
//               cloud without points is a valid PLY of no vertices
//   floor plan  <stem>.yaml + <stem>.pgm in the ROS map_server format (io/occupancy_grid_file.h), the YAML's
//               comments giving the map frame (T_mw) and the floor plane (occupancy.yaml, occupancy.pgm)
// Each throws core::Error naming the file that cannot be written.
#include <string>

#include "amos/dense/dense_map.h"

namespace amos::dense {

void writeMeshPly(const std::string& path, const DenseMesh& mesh);
void writeCloudPly(const std::string& path, const DenseCloud& cloud);
// `yaml_path` ends in .yaml; the PGM is written beside it with the same stem.
void writeFloorPlan(const std::string& yaml_path, const OccupancyGrid& grid, const FloorPlane& floor);

}  // namespace amos::dense
