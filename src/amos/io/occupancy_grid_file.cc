#include "amos/io/occupancy_grid_file.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"

namespace amos::io {
namespace fs = std::filesystem;
namespace {

std::string where(const std::string& file, const YAML::Node& node) {
  return fmt::format("{}:{}", file, node.Mark().line + 1);
}

template <typename T>
T required(const YAML::Node& root, const char* key, const std::string& file) {
  const YAML::Node node = root[key];
  core::require(node.IsDefined() && !node.IsNull(), fmt::format("{}: no key '{}'", file, key));
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw core::Error(fmt::format("{}: key '{}' has a value of the wrong type", where(file, node), key));
  }
}

template <typename T>
void optional(const YAML::Node& root, const char* key, const std::string& file, T& value) {
  if (root[key].IsDefined() && !root[key].IsNull()) value = required<T>(root, key, file);
}

YAML::Node loadYaml(const std::string& path) {
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw core::Error(fmt::format("{}: cannot read it as YAML: {}", path, e.what()));
  }
}

}  // namespace

void writeOccupancyGridFile(const std::string& yaml_path, const OccupancyGridFile& grid,
                            const std::vector<std::string>& comment_lines) {
  core::require(grid.width > 0 && grid.height > 0 &&
                    grid.cells.size() == static_cast<std::size_t>(grid.width) * grid.height,
                fmt::format("{}: the grid has {} cells for {} x {}", yaml_path, grid.cells.size(), grid.width,
                            grid.height));
  const fs::path yaml(yaml_path);
  const std::string image = grid.image_file.empty() ? yaml.stem().string() + ".pgm" : grid.image_file;
  std::string pgm = fmt::format("P5\n# amos-slam occupancy grid: 254 free, 0 occupied, 205 unknown\n{} {}\n255\n",
                                grid.width, grid.height);
  pgm.append(grid.cells.begin(), grid.cells.end());
  const fs::path image_path = fs::path(image).is_absolute() ? fs::path(image) : yaml.parent_path() / image;
  writeFileAtomically(image_path.string(), pgm);
  std::string text;
  for (const std::string& line : comment_lines) text += "# " + line + "\n";
  text += fmt::format(
      "image: {}\nmode: trinary\nresolution: {}\norigin: [{:.6f}, {:.6f}, {}]\nnegate: {}\n"
      "occupied_thresh: {}\nfree_thresh: {}\n",
      image, grid.resolution, grid.origin[0], grid.origin[1],
      grid.origin[2] == 0 ? std::string("0.0") : fmt::format("{}", grid.origin[2]), grid.negate ? 1 : 0,
      grid.occupied_thresh, grid.free_thresh);
  writeFileAtomically(yaml_path, text);
}

OccupancyGridFile readOccupancyGridFile(const std::string& yaml_path) {
  const YAML::Node root = loadYaml(yaml_path);
  core::require(root.IsMap(), fmt::format("{}: not a map_server grid description (no keys)", yaml_path));
  OccupancyGridFile g;
  g.image_file = required<std::string>(root, "image", yaml_path);
  g.resolution = required<double>(root, "resolution", yaml_path);
  core::require(g.resolution > 0 && std::isfinite(g.resolution),
                fmt::format("{}: 'resolution' must be a positive number of metres per cell",
                            where(yaml_path, root["resolution"])));
  const auto origin = required<std::vector<double>>(root, "origin", yaml_path);
  core::require(origin.size() == 3, fmt::format("{}: 'origin' must be [x, y, yaw]", where(yaml_path, root["origin"])));
  std::copy(origin.begin(), origin.end(), g.origin.begin());
  int negate = 0;
  optional(root, "negate", yaml_path, negate);
  g.negate = negate != 0;
  optional(root, "occupied_thresh", yaml_path, g.occupied_thresh);
  optional(root, "free_thresh", yaml_path, g.free_thresh);
  fs::path image = g.image_file;
  if (image.is_relative()) image = fs::path(yaml_path).parent_path() / image;
  const cv::Mat pixels = cv::imread(image.string(), cv::IMREAD_GRAYSCALE);
  core::require(!pixels.empty(),
                fmt::format("{}: the image it names, {}, cannot be read", yaml_path, image.string()));
  g.width = pixels.cols;
  g.height = pixels.rows;
  g.cells.reserve(pixels.total());
  for (int r = 0; r < pixels.rows; ++r) g.cells.insert(g.cells.end(), pixels.ptr(r), pixels.ptr(r) + pixels.cols);
  return g;
}

}  // namespace amos::io
