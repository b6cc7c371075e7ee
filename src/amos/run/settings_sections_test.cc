#include "amos/config/dense_section.h"

#include <gtest/gtest.h>

#include "amos/config/settings.h"
#include "amos/core/error.h"

namespace amos::config {
namespace {

const char* kCamera = "Camera.fx: 500\nCamera.fy: 500\nCamera.cx: 320\nCamera.cy: 240\n";

TEST(DenseSection, ReadsTheDenseKeys) {
  const Settings s = parseSettings(std::string(kCamera) + "Dense.voxelSize: 0.01\nDense.truncation: 0.04\n"
                                   "Dense.maskMargin: 6\nDense.gridResolution: 0.1\n", "dense.yaml");
  EXPECT_DOUBLE_EQ(s.dense.voxel_size, 0.01);
  EXPECT_DOUBLE_EQ(s.dense.truncation, 0.04);
  EXPECT_EQ(s.dense.mask_margin_px, 6);
  EXPECT_DOUBLE_EQ(s.dense.grid_resolution, 0.1);
}

TEST(DenseSection, RefusesBadValuesNamingTheKeyAndLine) {
  const struct {
    const char* yaml;
    const char* key;
  } cases[] = {{"Dense.voxelSize: -0.02\n", "Dense.voxelSize"},
               {"Dense.truncation: 0.03\n", "Dense.truncation"},
               {"Dense.maxDepth: 0.2\n", "Dense.maxDepth"},
               {"Dense.scale: 1.5\n", "Dense.scale"},
               {"Dense.frameStep: 0\n", "Dense.frameStep"},
               {"Dense.gridMaxHeight: 0.05\n", "Dense.gridMaxHeight"}};
  for (const auto& c : cases) {
    try {
      parseSettings(std::string(kCamera) + c.yaml, "dense.yaml");
      ADD_FAILURE() << "accepted " << c.yaml;
    } catch (const core::Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(c.key), std::string::npos) << message;
      EXPECT_NE(message.find("dense.yaml:5"), std::string::npos) << message;
    }
  }
}

TEST(DenseSection, ListsEveryKeyInTheKeyTables) {
  const std::string tables = keysMarkdown();
  for (const char* key : {"Dense.voxelSize", "Dense.truncation", "Dense.maskMargin", "Dense.edgeJump", "Dense.scale",
                          "Dense.frameStep", "Dense.liveEvery", "Dense.gridResolution"})
    EXPECT_NE(tables.find(std::string("`") + key + "`"), std::string::npos) << key;
}

}  // namespace
}  // namespace amos::config
