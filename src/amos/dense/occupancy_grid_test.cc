#include "amos/dense/occupancy_grid.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "amos/core/error.h"

namespace amos::dense {
namespace {

namespace fs = std::filesystem;

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
  const int row = grid.cells.rows - 1 - int(std::floor((m.y() - grid.origin.y()) / grid.resolution));
  if (column < 0 || row < 0 || column >= grid.cells.cols || row >= grid.cells.rows) return kUnknownCell;
  return grid.cells.at<unsigned char>(row, column);
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
  EXPECT_NEAR(grid.cells.cols * grid.resolution, 4.0, 0.3);
}

TEST(OccupancyGrid, ReadsBackWhatItWroteInTheMapServerFormat) {
  const fs::path dir = fs::temp_directory_path() / ("amos_grid_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  FloorPlane floor;
  const OccupancyGrid grid = buildOccupancyGrid(scene(), floor, {0, 0, 1.4}, {1, 0, 0}, DenseOptions{});
  writeOccupancyGrid(dir.string(), "occupancy", grid, floor);
  const OccupancyGrid back = readOccupancyGrid((dir / "occupancy.yaml").string());
  EXPECT_EQ(cv::countNonZero(back.cells != grid.cells), 0);
  EXPECT_DOUBLE_EQ(back.resolution, grid.resolution);
  EXPECT_NEAR(back.origin.x(), grid.origin.x(), 1e-6);
  EXPECT_NEAR(back.origin.y(), grid.origin.y(), 1e-6);
  std::ifstream yaml(dir / "occupancy.yaml");
  const std::string text((std::istreambuf_iterator<char>(yaml)), std::istreambuf_iterator<char>());
  for (const char* key : {"image: occupancy.pgm", "mode: trinary", "negate: 0", "occupied_thresh: 0.65",
                          "free_thresh: 0.196"})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  fs::remove_all(dir);
}

TEST(OccupancyGrid, ReadingAMapWithoutResolutionNamesTheKey) {
  const fs::path dir = fs::temp_directory_path() / ("amos_grid_bad_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "map.yaml") << "image: map.pgm\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  try {
    readOccupancyGrid((dir / "map.yaml").string());
    FAIL() << "accepted a map without resolution";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("resolution"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace amos::dense
