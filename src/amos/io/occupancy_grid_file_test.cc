#include "amos/io/occupancy_grid_file.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"

namespace amos::io {
namespace {

namespace fs = std::filesystem;

std::string textOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

OccupancyGridFile smallGrid() {
  OccupancyGridFile g;
  g.width = 4;
  g.height = 3;
  g.cells = {kUnknownCell, kFreeCell, kFreeCell, kOccupiedCell, kFreeCell, kFreeCell,
             kFreeCell,    kFreeCell, kOccupiedCell, kUnknownCell, kUnknownCell, kFreeCell};
  g.resolution = 0.05;
  g.origin = {-1.25, 0.5, 0};
  return g;
}

TEST(OccupancyGridFile, ReadsBackWhatItWroteInTheMapServerFormat) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_grid_file_");
  writeOccupancyGridFile((dir / "floor.yaml").string(), smallGrid(), {"a comment"});
  const OccupancyGridFile back = readOccupancyGridFile((dir / "floor.yaml").string());
  EXPECT_EQ(back.width, 4);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.cells, smallGrid().cells);
  EXPECT_EQ(back.at(0, 3), kOccupiedCell);
  EXPECT_DOUBLE_EQ(back.resolution, 0.05);
  EXPECT_DOUBLE_EQ(back.origin[0], -1.25);
  EXPECT_EQ(back.image_file, "floor.pgm");
  const std::string yaml = textOf(dir / "floor.yaml");
  EXPECT_EQ(yaml.rfind("# a comment\n", 0), 0u) << yaml;
  for (const char* line : {"image: floor.pgm\n", "mode: trinary\n", "origin: [-1.250000, 0.500000, 0.0]\n",
                           "negate: 0\n", "occupied_thresh: 0.65\n", "free_thresh: 0.196\n"})
    EXPECT_NE(yaml.find(line), std::string::npos) << line;
  EXPECT_EQ(textOf(dir / "floor.pgm").rfind("P5\n", 0), 0u);
  EXPECT_FALSE(fs::exists(dir / "floor.yaml.partial"));
  fs::remove_all(dir);
}

TEST(OccupancyGridFile, AGridWhoseCellsDoNotFitItsSizeIsRefused) {
  OccupancyGridFile g = smallGrid();
  g.cells.pop_back();
  EXPECT_THROW(writeOccupancyGridFile((fs::temp_directory_path() / "never.yaml").string(), g), core::Error);
}

TEST(OccupancyGridFile, ReadingAMapWithoutResolutionNamesTheKey) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_grid_file_");
  std::ofstream(dir / "map.yaml") << "image: map.pgm\norigin: [0, 0, 0]\nnegate: 0\n";
  try {
    readOccupancyGridFile((dir / "map.yaml").string());
    ADD_FAILURE() << "accepted a map without resolution";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("'resolution'"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace amos::io

namespace amos::io {
namespace {

// A crafted floor plan: the header claims 60000 x 60000 pixels (3.6 GB) and the file holds a few bytes. It must be
// refused from the header, naming the PGM, before anything that size is allocated.
TEST(OccupancyGridFile, APgmHeaderClaimingMoreThanTheFileHoldsIsRefusedBeforeAllocating) {
  const fs::path dir = amos::testing::scratchDirForThisTest("amos_grid_file_");
  std::ofstream(dir / "map.yaml") << "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n";
  std::ofstream(dir / "map.pgm", std::ios::binary) << "P5\n# crafted\n60000 60000\n255\n\x01\x02\x03\x04";
  const auto start = std::chrono::steady_clock::now();
  try {
    readOccupancyGridFile((dir / "map.yaml").string());
    ADD_FAILURE() << "accepted a PGM whose header claims more than the file holds";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("map.pgm"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("60000 x 60000"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace amos::io
