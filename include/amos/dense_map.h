#pragma once
// The dense static map as plain data (Options::dense; Slam::denseMap, Slam::denseSnapshot) and its files: what
// `amos-slam run --dense` writes (docs/dense.md). All in the world frame of the trajectory (T_wc) it was fused with.
//
//   amos::Options options;  options.settings_file = "configs/tum2.yaml";  options.dense = true;
//   amos::Slam slam(options);   ... track() every frame ...   slam.finish();
//   const amos::DenseMap map = slam.denseMap();    // fused with the final trajectory
//   amos::writeMeshPly(map, "mesh.ply");
//   if (map.grid) amos::writeFloorPlan(map, "occupancy");   // occupancy.pgm + occupancy.yaml
//
// Only in a library built with Open3D (denseMappingAvailable()); the writers throw std::runtime_error otherwise,
// and when a file cannot be written (naming it).
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace amos {

using Rgb = std::array<std::uint8_t, 3>;  // R, G, B

// A coloured triangle mesh (marching cubes of the TSDF volume).
struct DenseMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3d> normals;                 // per vertex, unit, or empty
  std::vector<Rgb> colours;                             // per vertex, or empty
  std::vector<std::array<std::uint32_t, 3>> triangles;  // vertex indices, counter-clockwise seen from outside
};

// Points with their colours (and normals when the source has them).
struct DenseCloud {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> normals;  // unit, or empty
  std::vector<Rgb> colours;              // one per point, or empty
};

// The floor plan: a 2D occupancy grid with the ROS map_server meaning of its cells.
struct OccupancyGrid {
  static constexpr std::uint8_t kFree = 254, kOccupied = 0, kUnknown = 205;
  int rows = 0, cols = 0;
  std::vector<std::uint8_t> cells;  // rows x cols, row by row; row 0 is the top (the largest map y), as in the PGM
  double resolution = 0.05;         // m per cell
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();     // map-frame x, y of the lower-left cell's corner
  Eigen::Matrix4d T_mw = Eigen::Matrix4d::Identity();   // world -> map frame (on the floor, z up)
  Eigen::Vector3d floor_normal = Eigen::Vector3d::UnitZ();  // the floor in the world: normal . p + offset = 0
  double floor_offset = 0;

  std::uint8_t at(int row, int col) const { return cells[static_cast<std::size_t>(row) * cols + col]; }
};

// The final map (Slam::denseMap).
struct DenseMap {
  DenseMesh mesh;
  DenseCloud cloud;                   // the surface's points (the TSDF's zero crossings)
  DenseCloud removed;                 // the dynamic readings left out of fusion, one per voxel
  std::optional<OccupancyGrid> grid;  // the floor plan, when a floor was found
  std::size_t frames_fused = 0;
};

// The live volume's surface while running (Slam::denseSnapshot), in the world frame of the tracking poses,
// downsampled to Dense.liveCloudVoxel.
struct DenseSnapshot {
  DenseCloud cloud;  // points and colours
  std::size_t frames_fused = 0;
};

// Whether this library was built with the dense map (Open3D).
bool denseMappingAvailable();

// The mesh as a binary PLY with vertex normals and colours (run --dense's mesh.ply).
void writeMeshPly(const DenseMap& map, const std::string& path);
// The surface cloud as a binary PLY (run --dense's cloud.ply).
void writeCloudPly(const DenseMap& map, const std::string& path);
// The floor plan as <stem>.pgm + <stem>.yaml (ROS map_server format; run --dense's occupancy.*). An error when the
// map has none (grid empty).
void writeFloorPlan(const DenseMap& map, const std::string& stem);

}  // namespace amos
