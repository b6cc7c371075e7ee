#include "amos/viewer/occupancy_grid.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"
#include "amos/testing/scratch_dir.h"
#include "amos/viewer/test_run_folder.h"

namespace amos::viewer {
namespace {

namespace fs = std::filesystem;

TEST(OccupancyGrid, ReadsTheMapServerFormatAndCountsCells) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_occupancy_");
  test::writeOccupancy(dir, 40, 20, 0.05);
  const OccupancyGrid g = readOccupancyGrid(dir / "occupancy.yaml");
  EXPECT_EQ(g.image.cols, 40);
  EXPECT_EQ(g.image.rows, 20);
  EXPECT_DOUBLE_EQ(g.resolution, 0.05);
  EXPECT_DOUBLE_EQ(g.origin[0], -1.5);
  EXPECT_DOUBLE_EQ(g.origin[1], -2.0);
  EXPECT_FALSE(g.negate);
  EXPECT_EQ(g.image.at<unsigned char>(5, 0), 205);   // unknown quarter
  EXPECT_EQ(g.image.at<unsigned char>(0, 20), 0);    // occupied border
  EXPECT_EQ(g.image.at<unsigned char>(5, 20), 254);  // free inside
  const nlohmann::json j = occupancyReportJson(g);
  // Unknown: columns 0..9 (10 x 20); occupied: the border right of them; free: the rest.
  EXPECT_EQ(j["cells"]["unknown"], 200);
  EXPECT_EQ(j["cells"]["occupied"], 30 * 2 + 18);
  EXPECT_EQ(j["cells"]["free"], 800 - 200 - 78);
  EXPECT_EQ(j["width"], 40);
  EXPECT_GT(j["png"].get<std::string>().size(), 20u);
}

TEST(OccupancyGrid, BadDescriptionsAreErrorsNamingTheFileAndKey) {
  const fs::path dir = amos::testing::scratchDirForThisTest("viewer_occupancy_");
  test::writeOccupancy(dir, 8, 8, 0.1);
  auto message = [&](const std::string& yaml) {
    test::writeText(dir / "bad.yaml", yaml);
    try {
      readOccupancyGrid(dir / "bad.yaml");
    } catch (const core::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string origin = "origin: [0, 0, 0]\n";
  EXPECT_NE(message("resolution: 0.1\n" + origin).find("'image'"), std::string::npos);
  EXPECT_NE(message("image: occupancy.pgm\nresolution: -1\n" + origin).find("bad.yaml:2"), std::string::npos);
  EXPECT_NE(message("image: occupancy.pgm\nresolution: 0.1\norigin: [0, 0]\n").find("origin"), std::string::npos);
  EXPECT_NE(message("image: missing.pgm\nresolution: 0.1\n" + origin).find("missing.pgm"), std::string::npos);
  EXPECT_NE(message("image: occupancy.pgm\nresolution: fine\n" + origin).find("'resolution'"), std::string::npos);
  EXPECT_NE(message("[1, 2").find("bad.yaml"), std::string::npos);
}

}  // namespace
}  // namespace amos::viewer
