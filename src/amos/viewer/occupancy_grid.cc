#include "amos/viewer/occupancy_grid.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "amos/core/error.h"
#include "amos/viewer/base64.h"

namespace amos::viewer {
namespace fs = std::filesystem;
namespace {

std::string where(const fs::path& file, const YAML::Node& node) {
  return fmt::format("{}:{}", file.string(), node.Mark().line + 1);
}

template <typename T>
T required(const YAML::Node& root, const char* key, const fs::path& file) {
  const YAML::Node node = root[key];
  core::require(node.IsDefined() && !node.IsNull(), fmt::format("{}: no key '{}'", file.string(), key));
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw core::Error(fmt::format("{}: key '{}' has a value of the wrong type", where(file, node), key));
  }
}

template <typename T>
void optional(const YAML::Node& root, const char* key, const fs::path& file, T& value) {
  if (root[key].IsDefined() && !root[key].IsNull()) value = required<T>(root, key, file);
}

}  // namespace

OccupancyGrid readOccupancyGrid(const fs::path& yaml) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml.string());
  } catch (const YAML::Exception& e) {
    throw core::Error(fmt::format("{}: cannot read it as YAML: {}", yaml.string(), e.what()));
  }
  core::require(root.IsMap(), fmt::format("{}: not a map_server grid description (no keys)", yaml.string()));
  OccupancyGrid g;
  g.image_file = required<std::string>(root, "image", yaml);
  g.resolution = required<double>(root, "resolution", yaml);
  core::require(g.resolution > 0 && std::isfinite(g.resolution),
                fmt::format("{}: 'resolution' must be a positive number of metres per cell", where(yaml, root["resolution"])));
  const auto origin = required<std::vector<double>>(root, "origin", yaml);
  core::require(origin.size() == 3, fmt::format("{}: 'origin' must be [x, y, yaw]", where(yaml, root["origin"])));
  std::copy(origin.begin(), origin.end(), g.origin.begin());
  int negate = 0;
  optional(root, "negate", yaml, negate);
  g.negate = negate != 0;
  optional(root, "occupied_thresh", yaml, g.occupied_thresh);
  optional(root, "free_thresh", yaml, g.free_thresh);
  fs::path image = g.image_file;
  if (image.is_relative()) image = yaml.parent_path() / image;
  g.image = cv::imread(image.string(), cv::IMREAD_GRAYSCALE);
  core::require(!g.image.empty(), fmt::format("{}: the image it names, {}, cannot be read", yaml.string(), image.string()));
  return g;
}

nlohmann::json occupancyReportJson(const OccupancyGrid& g) {
  std::vector<unsigned char> png;
  cv::imencode(".png", g.image, png);
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
