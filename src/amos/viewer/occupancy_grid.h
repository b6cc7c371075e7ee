#pragma once
// The 2D occupancy grid of `run --dense` as report.html shows it: occupancy.yaml + occupancy.pgm in the format of
// the ROS map_server / Nav2 (yaml keys image, resolution, origin [x, y, yaw], negate, occupied_thresh,
// free_thresh; a P5 PGM, 254 free, 0 occupied, 205 unknown, row 0 at the top = the largest y), read by
// io/occupancy_grid_file.h.
#include <nlohmann/json.hpp>

#include <opencv2/core.hpp>

#include <array>
#include <filesystem>
#include <string>

namespace amos::viewer {

struct OccupancyGrid {
  cv::Mat image;                       // CV_8UC1, as in the PGM
  double resolution = 0;               // metres per cell
  std::array<double, 3> origin{};      // x, y (metres) of the lower-left cell, yaw (rad)
  bool negate = false;
  double occupied_thresh = 0.65, free_thresh = 0.196;
  std::string image_file;              // as the yaml names it
};

// Reads `yaml` and the image it names (relative to the yaml's folder when not absolute). Throws core::Error
// naming the file (and the key and line) when either cannot be read or a value is missing or out of range.
OccupancyGrid readOccupancyGrid(const std::filesystem::path& yaml);

// What report.html draws: {width, height, resolution, origin, png (base64 of the image as PNG), cells: {free,
// occupied, unknown} by the thresholds}.
nlohmann::json occupancyReportJson(const OccupancyGrid& grid);

}  // namespace amos::viewer
