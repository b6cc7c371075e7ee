#include "amos/io/occupancy_grid_file.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>


#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"
#include "amos/io/image_codecs.h"

namespace amos::io {
namespace fs = std::filesystem;
namespace {

// The next whitespace-separated number of a PNM header (skipping "#" comments), or -1 when there is none.
long long nextHeaderNumber(std::istream& in) {
  for (int c = in.peek(); c != EOF; c = in.peek()) {
    if (c == '#') {
      in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    } else if (std::isspace(c)) {
      in.get();
    } else {
      break;
    }
  }
  long long number = -1;
  if (!(in >> number)) return -1;
  return number;
}

// A binary PGM (P5) allocates width x height from its header before reading the pixels: the header must not claim
// more pixels than the file holds. Other formats are left to OpenCV.
void requirePgmFitsItsFile(const fs::path& image) {
  std::ifstream in(image, std::ios::binary);
  char magic[2] = {0, 0};
  if (!in.read(magic, 2) || magic[0] != 'P' || magic[1] != '5') return;
  const long long width = nextHeaderNumber(in), height = nextHeaderNumber(in), max_value = nextHeaderNumber(in);
  core::require(width > 0 && height > 0 && max_value > 0 && max_value <= 65535 && std::isspace(in.get()),
                fmt::format("{}: not a binary PGM header (P5 width height maxval)", image.string()));
  const long long bytes_per_pixel = max_value > 255 ? 2 : 1;
  const long long pixel_bytes = static_cast<long long>(fs::file_size(image)) - static_cast<long long>(in.tellg());
  core::require(width <= pixel_bytes && height <= pixel_bytes && width * height * bytes_per_pixel <= pixel_bytes,
                fmt::format("{}: the PGM header claims {} x {} pixels, but the file holds {} bytes of pixels",
                            image.string(), width, height, pixel_bytes));
}

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
  if (fs::is_regular_file(image)) requirePgmFitsItsFile(image);
  const cv::Mat pixels = readImage(image.string(), kReadGrayscale);
  core::require(!pixels.empty(),
                fmt::format("{}: the image it names, {}, cannot be read", yaml_path, image.string()));
  g.width = pixels.cols;
  g.height = pixels.rows;
  g.cells.reserve(pixels.total());
  for (int r = 0; r < pixels.rows; ++r) g.cells.insert(g.cells.end(), pixels.ptr(r), pixels.ptr(r) + pixels.cols);
  return g;
}

}  // namespace amos::io
