#include "amos/dense/dense_map_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/PointCloudIO.h>
#include <open3d/io/TriangleMeshIO.h>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"
#include "amos/io/occupancy_grid_file.h"

namespace amos::dense {
namespace {

namespace fs = std::filesystem;

DenseMesh triangle() {
  DenseMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.colours = {{255, 0, 0}, {0, 128, 0}, {1, 2, 3}};
  m.triangles = {{0, 1, 2}};
  return m;
}

TEST(DenseMapFiles, WritesTheMeshAndCloudAsOpen3DReadsThem) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_files_");
  writeMeshPly((dir / "mesh.ply").string(), triangle());
  open3d::geometry::TriangleMesh mesh;
  ASSERT_TRUE(open3d::io::ReadTriangleMesh((dir / "mesh.ply").string(), mesh));
  ASSERT_EQ(mesh.vertices_.size(), 3u);
  EXPECT_EQ(mesh.triangles_.size(), 1u);
  EXPECT_NEAR(mesh.vertex_colors_[1].y() * 255, 128, 1e-9);
  DenseCloud cloud{triangle().vertices, {}, triangle().colours};
  writeCloudPly((dir / "cloud.ply").string(), cloud);
  open3d::geometry::PointCloud back;
  ASSERT_TRUE(open3d::io::ReadPointCloud((dir / "cloud.ply").string(), back));
  EXPECT_EQ(back.points_.size(), 3u);
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find("partial"), std::string::npos) << entry.path();
  fs::remove_all(dir);
}

TEST(DenseMapFiles, AnEmptyCloudIsAPlyWithoutVertices) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_files_");
  writeCloudPly((dir / "removed.ply").string(), DenseCloud{});
  std::ifstream in(dir / "removed.ply");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str().rfind("ply\nformat binary_little_endian 1.0\nelement vertex 0\n", 0), 0u);
  fs::remove_all(dir);
}

TEST(DenseMapFiles, AFileThatCannotBeWrittenIsAnErrorNamingItAndLeavesNoPartialFile) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_files_");
  const fs::path missing = dir / "no_such_folder" / "mesh.ply";
  try {
    writeMeshPly(missing.string(), triangle());
    ADD_FAILURE() << "wrote into a missing folder";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(DenseMapFiles, TheFloorPlanIsAMapServerGridWithItsFrameInTheComments) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_dense_files_");
  OccupancyGrid grid;
  grid.width = 2;
  grid.height = 1;
  grid.cells = {kFreeCell, kOccupiedCell};
  grid.origin = {-0.5, 0.25};
  writeFloorPlan((dir / "occupancy.yaml").string(), grid, FloorPlane{});
  const io::OccupancyGridFile back = io::readOccupancyGridFile((dir / "occupancy.yaml").string());
  EXPECT_EQ(back.cells, grid.cells);
  EXPECT_EQ(back.image_file, "occupancy.pgm");
  std::ifstream in(dir / "occupancy.yaml");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("#   T_mw: ["), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("# Floor plane in the world"), std::string::npos) << text.str();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace amos::dense
