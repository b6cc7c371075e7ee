#pragma once
// The floor plan as a 2D occupancy grid in the format of the ROS map_server / Nav2 map_server: a PGM image
// (254 free, 0 occupied, 205 unknown; row 0 is the far +y edge) and a YAML file (image, mode trinary, resolution,
// origin [x, y, yaw] of the lower-left pixel, negate, occupied_thresh, free_thresh). The map frame stands on the
// floor: z along the floor's normal (up), x the cameras' mean viewing direction laid on the floor, origin below
// the first camera. A cell is occupied where the dense map has surface between gridMinHeight and gridMaxHeight
// above the floor, free where the floor itself was seen and nothing stands on it, unknown elsewhere.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include <Eigen/Core>

#include "amos/core/pose.h"
#include "amos/dense/dense_options.h"
#include "amos/dense/floor_plane.h"

namespace amos::dense {

inline constexpr unsigned char kFreeCell = 254, kOccupiedCell = 0, kUnknownCell = 205;

struct OccupancyGrid {
  cv::Mat cells;                           // CV_8U: kFreeCell, kOccupiedCell or kUnknownCell
  double resolution = 0.05;                // m per cell
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // map-frame x, y of the lower-left pixel's corner
  core::SE3 T_mw = core::SE3::Identity();  // world -> map frame (on the floor, z up)
  int count(unsigned char value) const;
};

// `points`: the surface (world frame). `first_camera_centre` and `mean_forward` (world) place the map frame.
OccupancyGrid buildOccupancyGrid(const std::vector<Eigen::Vector3d>& points, const FloorPlane& floor,
                                 const Eigen::Vector3d& first_camera_centre, const Eigen::Vector3d& mean_forward,
                                 const DenseOptions& options);

// Writes <dir>/<stem>.pgm and <dir>/<stem>.yaml (the YAML's comments give T_mw and the floor plane). Throws
// core::Error naming the file that cannot be written.
void writeOccupancyGrid(const std::string& dir, const std::string& stem, const OccupancyGrid& grid,
                        const FloorPlane& floor);
// Reads a map_server YAML and the PGM it names (for tests and tools): cells, resolution and origin; T_mw is left at
// identity. Throws core::Error naming the file and what is wrong.
OccupancyGrid readOccupancyGrid(const std::string& yaml_path);

}  // namespace amos::dense
