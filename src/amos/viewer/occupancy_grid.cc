#include "amos/viewer/occupancy_grid.h"


#include <utility>
#include <vector>

#include "amos/io/image_codecs.h"
#include "amos/io/occupancy_grid_file.h"
#include "amos/viewer/base64.h"

namespace amos::viewer {

OccupancyGrid readOccupancyGrid(const std::filesystem::path& yaml) {
  io::OccupancyGridFile file = io::readOccupancyGridFile(yaml.string());
  OccupancyGrid g;
  g.image = cv::Mat(file.height, file.width, CV_8UC1, file.cells.data()).clone();
  g.resolution = file.resolution;
  g.origin = file.origin;
  g.negate = file.negate;
  g.occupied_thresh = file.occupied_thresh;
  g.free_thresh = file.free_thresh;
  g.image_file = std::move(file.image_file);
  return g;
}

nlohmann::json occupancyReportJson(const OccupancyGrid& g) {
  const std::vector<std::uint8_t> png = io::encodeImage(".png", g.image);
  // map_server's trinary reading: p = (255 - value) / 255 (value / 255 with negate), occupied above
  // occupied_thresh, free below free_thresh, unknown between.
  std::size_t free = 0, occupied = 0, unknown = 0;
  for (int r = 0; r < g.image.rows; ++r)
    for (int c = 0; c < g.image.cols; ++c) {
      const double v = g.image.at<unsigned char>(r, c) / 255.0;
      const double p = g.negate ? v : 1.0 - v;
      if (p > g.occupied_thresh) ++occupied;
      else if (p < g.free_thresh) ++free;
      else ++unknown;
    }
  return {{"width", g.image.cols},
          {"height", g.image.rows},
          {"resolution", g.resolution},
          {"origin", g.origin},
          {"image", g.image_file},
          {"png", base64Encode(png)},
          {"cells", {{"free", free}, {"occupied", occupied}, {"unknown", unknown}}}};
}

}  // namespace amos::viewer
