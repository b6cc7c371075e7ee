#include "amos/dense/occupancy_grid.h"

#include <gtest/gtest.h>

#include <cmath>

#include "amos/core/error.h"

namespace amos::dense {
namespace {

// Floor points over [-2, 2]^2 at z = 0, a box 0.5 m high over [0.5, 1]^2, a lamp at 2.2 m over [-1.5, -1]^2 (above
// the band: not an obstacle).
std::vector<Eigen::Vector3d> scene() {
  std::vector<Eigen::Vector3d> p;
  for (double x = -2; x <= 2; x += 0.02)
    for (double y = -2; y <= 2; y += 0.02) {
      const bool under_box = x >= 0.5 && x <= 1 && y >= 0.5 && y <= 1;
      if (!under_box) p.emplace_back(x, y, 0.0);
    }
  for (double x = 0.5; x <= 1; x += 0.02)
    for (double y = 0.5; y <= 1; y += 0.02) p.emplace_back(x, y, 0.5);
  for (double x = -1.5; x <= -1; x += 0.02)
    for (double y = -1.5; y <= -1; y += 0.02) p.emplace_back(x, y, 2.2);
  return p;
}

unsigned char cellAt(const OccupancyGrid& grid, const Eigen::Vector3d& world) {
  const Eigen::Vector3d m = grid.T_mw * world;
  const int column = int(std::floor((m.x() - grid.origin.x()) / grid.resolution));
  const int row = grid.height - 1 - int(std::floor((m.y() - grid.origin.y()) / grid.resolution));
  if (column < 0 || row < 0 || column >= grid.width || row >= grid.height) return kUnknownCell;
  return grid.at(row, column);
}

TEST(OccupancyGrid, MarksObstaclesInTheBandFreeFloorAndUnknownElsewhere) {
  FloorPlane floor;  // z = 0, up +z
  DenseOptions o;
  const OccupancyGrid grid = buildOccupancyGrid(scene(), floor, {0, 0, 1.4}, {1, 0, -0.3}, o);
  EXPECT_EQ(cellAt(grid, {0.75, 0.75, 0}), kOccupiedCell);
  EXPECT_EQ(cellAt(grid, {-0.5, 0.3, 0}), kFreeCell);
  EXPECT_EQ(cellAt(grid, {-1.25, -1.25, 0}), kFreeCell);  // under the lamp
  EXPECT_EQ(cellAt(grid, {5, 5, 0}), kUnknownCell);
  // The map's x axis is the cameras' forward direction laid on the floor, its origin under the first camera.
  EXPECT_TRUE((grid.T_mw * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 0, 0), 1e-9));
  EXPECT_NEAR(grid.width * grid.resolution, 4.0, 0.3);
}

TEST(OccupancyGrid, RefusesAGridTooLargeForMemoryNamingItsSize) {
  std::vector<Eigen::Vector3d> points = scene();
  points.emplace_back(2000, 2000, 0.0);  // a stray floor point 2 km away: 40000 x 40000 cells of 5 cm
  try {
    buildOccupancyGrid(points, FloorPlane{}, {0, 0, 1.4}, {1, 0, 0}, DenseOptions{});
    ADD_FAILURE() << "built a grid of 1.6e9 cells";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("the floor plan would have"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace amos::dense
