#pragma once
// A 2D occupancy grid in the format of the ROS map_server / Nav2 map_server: a YAML description (image, mode,
// resolution, origin [x, y, yaw] of the lower-left pixel, negate, occupied_thresh, free_thresh) and the image it
// names (a P5 PGM when written here: 254 free, 0 occupied, 205 unknown; row 0 is the far +y edge). The one reader
// and writer of the format: the dense map writes its floor plan with it, the viewer's report reads it back.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace amos::io {

inline constexpr std::uint8_t kFreeCell = 254, kOccupiedCell = 0, kUnknownCell = 205;

struct OccupancyGridFile {
  int width = 0, height = 0;
  std::vector<std::uint8_t> cells;  // width x height, row by row, row 0 at the top (the largest y)
  double resolution = 0.05;         // metres per cell
  std::array<double, 3> origin{};   // x, y (metres) of the lower-left cell's corner, yaw (rad)
  bool negate = false;
  double occupied_thresh = 0.65, free_thresh = 0.196;
  std::string image_file;           // as the YAML names it, relative to the YAML's folder unless absolute

  std::uint8_t at(int row, int column) const { return cells[static_cast<std::size_t>(row) * width + column]; }
};

// Writes `yaml_path` (with `comment_lines` as "# " comments at its top, mode trinary) and, beside it, the PGM that
// grid.image_file names (written as <yaml stem>.pgm when empty), each atomically (atomic_file.h). Throws
// core::Error naming the file that cannot be written.
void writeOccupancyGridFile(const std::string& yaml_path, const OccupancyGridFile& grid,
                            const std::vector<std::string>& comment_lines = {});

// Reads `yaml_path` and the image it names (any format OpenCV reads; grey levels kept). Throws core::Error naming
// the file (and the key and line) when either cannot be read or a value is missing or out of range.
OccupancyGridFile readOccupancyGridFile(const std::string& yaml_path);

}  // namespace amos::io
