#include "amos/dense/occupancy_grid.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "amos/core/error.h"

namespace amos::dense {

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

int OccupancyGrid::count(std::uint8_t value) const {
  return static_cast<int>(std::count(cells.begin(), cells.end(), value));
}

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
  core::require(static_cast<double>(width) * height <= kMaxGridCells,
                fmt::format("the floor plan would have {} x {} cells of {} m (more than {:g}): the map spans {:.0f} x "
                            "{:.0f} m",
                            width, height, r, kMaxGridCells, high.x() - low.x(), high.y() - low.y()));
  grid.width = width;
  grid.height = height;
  grid.cells.assign(static_cast<std::size_t>(width) * height, kUnknownCell);
  auto cell = [&](const Eigen::Vector3d& m) -> std::uint8_t& {
    const int column = static_cast<int>(std::floor((m.x() - grid.origin.x()) / r));
    const int row_from_bottom = static_cast<int>(std::floor((m.y() - grid.origin.y()) / r));
    return grid.cells[static_cast<std::size_t>(height - 1 - row_from_bottom) * width + column];
  };
  for (const auto& m : floor_points) cell(m) = kFreeCell;
  for (const auto& m : obstacle_points) cell(m) = kOccupiedCell;  // after the floor: an obstacle wins its cell
  return grid;
}

}  // namespace amos::dense
