#pragma once
// The dense map as plain data (no Open3D type): what DenseMapper gives, what dense_map_files.h writes, what a
// program using the library reads. All in the world frame of the trajectory the map was fused with.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "amos/dense/floor_plane.h"
#include "amos/dense/occupancy_grid.h"

namespace amos::dense {

using Rgb = std::array<std::uint8_t, 3>;

// Points with their colours (and normals when the source has them: empty otherwise).
struct DenseCloud {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> normals;  // unit, or empty
  std::vector<Rgb> colours;              // one per point, or empty
};

// A coloured triangle mesh (marching cubes of the TSDF).
struct DenseMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3d> normals;  // per vertex, unit, or empty (the TSDF's mesh has none)
  std::vector<Rgb> colours;              // per vertex, or empty
  std::vector<std::array<std::uint32_t, 3>> triangles;  // vertex indices, counter-clockwise seen from outside
};

struct DenseMap {
  DenseMesh mesh;
  DenseCloud cloud;    // the surface's points (the TSDF's zero crossings)
  DenseCloud removed;  // the dynamic readings left out of fusion, one per voxel
  std::optional<FloorPlane> floor;
  std::optional<OccupancyGrid> grid;  // the floor plan, when a floor was found
  std::string floor_plan_error;       // why there is no floor plan although the search ran ("" = none)
  nlohmann::json stats;               // stats.json's "dense" section
};

}  // namespace amos::dense
