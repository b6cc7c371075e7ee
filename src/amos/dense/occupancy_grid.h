#pragma once
// The floor plan as a 2D occupancy grid (written in the ROS map_server format by dense_map_files.h through
// io/occupancy_grid_file.h: 254 free, 0 occupied, 205 unknown; row 0 is the far +y edge). The map frame stands on
// the floor: z along the floor's normal (up), x the cameras' mean viewing direction laid on the floor, origin below
// the first camera. A cell is occupied where the dense map has surface between gridMinHeight and gridMaxHeight
// above the floor, free where the floor itself was seen and nothing stands on it, unknown elsewhere.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "amos/core/pose.h"
#include "amos/dense/dense_options.h"
#include "amos/dense/floor_plane.h"
#include "amos/io/occupancy_grid_file.h"

namespace amos::dense {

using io::kFreeCell;
using io::kOccupiedCell;
using io::kUnknownCell;

struct OccupancyGrid {
  int width = 0, height = 0;
  std::vector<std::uint8_t> cells;         // width x height, row by row, row 0 at the top (the largest map y)
  double resolution = 0.05;                // m per cell
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // map-frame x, y of the lower-left pixel's corner
  core::SE3 T_mw = core::SE3::Identity();  // world -> map frame (on the floor, z up)

  std::uint8_t at(int row, int column) const { return cells[static_cast<std::size_t>(row) * width + column]; }
  int count(std::uint8_t value) const;
};

// A floor plan larger than this is refused (a gigabyte of cells: a map hundreds of metres across at a fine
// Dense.gridResolution, or a stray point far away).
inline constexpr double kMaxGridCells = 1e9;

// `points`: the surface (world frame). `first_camera_centre` and `mean_forward` (world) place the map frame. Throws
// core::Error when the grid would have more than kMaxGridCells cells.
OccupancyGrid buildOccupancyGrid(const std::vector<Eigen::Vector3d>& points, const FloorPlane& floor,
                                 const Eigen::Vector3d& first_camera_centre, const Eigen::Vector3d& mean_forward,
                                 const DenseOptions& options);

}  // namespace amos::dense
