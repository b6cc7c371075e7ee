#include "amos/dense/occupancy_grid.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "amos/core/error.h"
#include "amos/io/atomic_file.h"

namespace amos::dense {

namespace fs = std::filesystem;

namespace {

// world -> map: rotation rows are the map axes in the world; the origin is the first camera's foot on the floor.
core::SE3 mapFrame(const FloorPlane& floor, const Eigen::Vector3d& first_centre, const Eigen::Vector3d& forward) {
  const Eigen::Vector3d z = floor.normal;
  Eigen::Vector3d x = forward - forward.dot(z) * z;
  if (x.norm() < 1e-6) x = z.unitOrthogonal();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R_mw;
  R_mw.row(0) = x.transpose();
  R_mw.row(1) = y.transpose();
  R_mw.row(2) = z.transpose();
  const Eigen::Vector3d origin_w = first_centre - floor.height(first_centre) * z;
  core::SE3 T_mw = core::SE3::Identity();
  T_mw.linear() = R_mw;
  T_mw.translation() = -R_mw * origin_w;
  return T_mw;
}

}  // namespace

int OccupancyGrid::count(unsigned char value) const { return cv::countNonZero(cells == value); }

OccupancyGrid buildOccupancyGrid(const std::vector<Eigen::Vector3d>& points, const FloorPlane& floor,
                                 const Eigen::Vector3d& first_camera_centre, const Eigen::Vector3d& mean_forward,
                                 const DenseOptions& options) {
  OccupancyGrid grid;
  grid.resolution = options.grid_resolution;
  grid.T_mw = mapFrame(floor, first_camera_centre, mean_forward);
  // A floor point: within the floor's thickness as the map holds it (a voxel's noise on each side, 3 cm at least).
  const double floor_band = std::max(0.03, 2 * options.voxel_size);
  std::vector<Eigen::Vector3d> floor_points, obstacle_points;
  for (const auto& p : points) {
    const Eigen::Vector3d m = grid.T_mw * p;
    if (std::abs(m.z()) <= floor_band) floor_points.push_back(m);
    else if (m.z() >= options.grid_min_height && m.z() <= options.grid_max_height) obstacle_points.push_back(m);
  }
  Eigen::Vector2d low(0, 0), high(0, 0);
  bool any = false;
  for (const auto* set : {&floor_points, &obstacle_points}) {
    for (const auto& m : *set) {
      low = any ? low.cwiseMin(m.head<2>()) : Eigen::Vector2d(m.head<2>());
      high = any ? high.cwiseMax(m.head<2>()) : Eigen::Vector2d(m.head<2>());
      any = true;
    }
  }
  const double r = grid.resolution;
  grid.origin = Eigen::Vector2d(std::floor(low.x() / r) - 1, std::floor(low.y() / r) - 1) * r;
  const int width = static_cast<int>(std::ceil((high.x() - grid.origin.x()) / r)) + 2;
  const int height = static_cast<int>(std::ceil((high.y() - grid.origin.y()) / r)) + 2;
  grid.cells = cv::Mat(height, width, CV_8U, cv::Scalar(kUnknownCell));
  auto cell = [&](const Eigen::Vector3d& m) -> unsigned char& {
    const int column = static_cast<int>(std::floor((m.x() - grid.origin.x()) / r));
    const int row_from_bottom = static_cast<int>(std::floor((m.y() - grid.origin.y()) / r));
    return grid.cells.at<unsigned char>(height - 1 - row_from_bottom, column);
  };
  for (const auto& m : floor_points) cell(m) = kFreeCell;
  for (const auto& m : obstacle_points) cell(m) = kOccupiedCell;  // after the floor: an obstacle wins its cell
  return grid;
}

void writeOccupancyGrid(const std::string& dir, const std::string& stem, const OccupancyGrid& grid,
                        const FloorPlane& floor) {
  std::string pgm = fmt::format("P5\n# amos-slam occupancy grid: 254 free, 0 occupied, 205 unknown\n{} {}\n255\n",
                                grid.cells.cols, grid.cells.rows);
  const cv::Mat cells = grid.cells.isContinuous() ? grid.cells : grid.cells.clone();
  pgm.append(reinterpret_cast<const char*>(cells.data), cells.total());
  io::writeFileAtomically((fs::path(dir) / (stem + ".pgm")).string(), pgm);
  const Eigen::Matrix4d T = grid.T_mw.matrix();
  std::string yaml = fmt::format(
      "# ROS map_server / Nav2 map: the floor plan of the dense static map (amos-slam run --dense).\n"
      "# Map frame: on the floor, z up. World (the trajectory's frame) -> map, row-major 4x4 (p_map = T_mw p_w):\n"
      "#   T_mw: [{}]\n"
      "# Floor plane in the world: normal . p + offset = 0, normal [{:.6f}, {:.6f}, {:.6f}], offset {:.6f}\n"
      "image: {}.pgm\nmode: trinary\nresolution: {}\norigin: [{:.6f}, {:.6f}, 0.0]\nnegate: 0\n"
      "occupied_thresh: 0.65\nfree_thresh: 0.196\n",
      fmt::join(T.data(), T.data() + 16, ", "), floor.normal.x(), floor.normal.y(), floor.normal.z(), floor.offset,
      stem, grid.resolution, grid.origin.x(), grid.origin.y());
  io::writeFileAtomically((fs::path(dir) / (stem + ".yaml")).string(), yaml);
}

namespace {

cv::Mat readPgm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  core::require(in.good(), fmt::format("{}: cannot be read", path));
  std::string magic;
  in >> magic;
  core::require(magic == "P5", fmt::format("{}: not a binary PGM (P5)", path));
  std::vector<int> numbers;
  while (numbers.size() < 3 && in) {
    in >> std::ws;
    if (in.peek() == '#') {
      std::string comment;
      std::getline(in, comment);
      continue;
    }
    int value = 0;
    in >> value;
    numbers.push_back(value);
  }
  core::require(numbers.size() == 3 && numbers[0] > 0 && numbers[1] > 0 && numbers[2] == 255,
                fmt::format("{}: bad PGM header", path));
  in.get();  // the one whitespace after maxval
  cv::Mat cells(numbers[1], numbers[0], CV_8U);
  in.read(reinterpret_cast<char*>(cells.data), static_cast<std::streamsize>(cells.total()));
  core::require(static_cast<std::size_t>(in.gcount()) == cells.total(), fmt::format("{}: truncated", path));
  return cells;
}

}  // namespace

OccupancyGrid readOccupancyGrid(const std::string& yaml_path) {
  YAML::Node node;
  try {
    node = YAML::LoadFile(yaml_path);
  } catch (const YAML::Exception& e) {
    throw core::Error(fmt::format("{}: {}", yaml_path, e.what()));
  }
  for (const char* key : {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"})
    core::require(static_cast<bool>(node[key]), fmt::format("{}: key '{}' is missing", yaml_path, key));
  OccupancyGrid grid;
  grid.resolution = node["resolution"].as<double>();
  const auto origin = node["origin"].as<std::vector<double>>();
  core::require(origin.size() == 3, fmt::format("{}: origin must be [x, y, yaw]", yaml_path));
  grid.origin = {origin[0], origin[1]};
  fs::path image = node["image"].as<std::string>();
  if (image.is_relative()) image = fs::path(yaml_path).parent_path() / image;
  grid.cells = readPgm(image.string());
  return grid;
}

}  // namespace amos::dense
