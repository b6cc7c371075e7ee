#include "amos/run/settings_sections.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"
#include "amos/dense/dense_options.h"

namespace amos::run {
namespace {

const char* kCamera = "Camera.fx: 500\nCamera.fy: 500\nCamera.cx: 320\nCamera.cy: 240\n";

config::Settings parse(const std::string& yaml) {
  return config::parseSettings(std::string(kCamera) + yaml, "dense.yaml", settingsSections());
}

TEST(SettingsSections, ReadsTheDenseKeys) {
  const config::Settings s =
      parse("Dense.voxelSize: 0.01\nDense.truncation: 0.04\nDense.maskMargin: 6\nDense.gridResolution: 0.1\n");
  const auto& dense = s.section<dense::DenseOptions>();
  EXPECT_DOUBLE_EQ(dense.voxel_size, 0.01);
  EXPECT_DOUBLE_EQ(dense.truncation, 0.04);
  EXPECT_EQ(dense.mask_margin_px, 6);
  EXPECT_DOUBLE_EQ(dense.grid_resolution, 0.1);
}

TEST(SettingsSections, RefusesBadDenseValuesNamingTheKeyAndLine) {
  const struct {
    const char* yaml;
    const char* key;
  } cases[] = {{"Dense.voxelSize: -0.02\n", "Dense.voxelSize"},
               {"Dense.truncation: 0.03\n", "Dense.truncation"},
               {"Dense.maxDepth: 0.2\n", "Dense.maxDepth"},
               {"Dense.scale: 1.5\n", "Dense.scale"},
               {"Dense.frameStep: 0\n", "Dense.frameStep"},
               {"Dense.gridMaxHeight: 0.05\n", "Dense.gridMaxHeight"},
               // Bounds from the keys' meaning (issue 51): finer than the sensor's noise, a cell below a
               // millimetre, a margin of half the image, a volume that does not fit in memory.
               {"Dense.voxelSize: 0.0001\n", "Dense.voxelSize"},
               {"Dense.gridResolution: 0.000001\n", "Dense.gridResolution"},
               {"Dense.maskMargin: 300\n", "Dense.maskMargin"},
               {"Dense.voxelSize: 0.003\nDense.truncation: 0.006\nDense.maxDepth: 10\n", "Dense.voxelSize"},
               {"Dense.queueFrames: 100000\n", "Dense.queueFrames"},
               {"Dense.maxDepth: 50\n", "Dense.maxDepth"}};
  for (const auto& c : cases) {
    try {
      parse(c.yaml);
      ADD_FAILURE() << "accepted " << c.yaml;
    } catch (const core::Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(c.key), std::string::npos) << message;
      EXPECT_NE(message.find("dense.yaml:5"), std::string::npos) << message;
    }
  }
}

TEST(SettingsSections, ABoundNamesTheSensorNoiseOrTheMemoryItComesFrom) {
  auto message = [](const std::string& yaml) {
    try {
      parse(yaml);
    } catch (const core::Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("Dense.voxelSize: 0.0001\n").find("depth noise at Dense.minDepth"), std::string::npos)
      << message("Dense.voxelSize: 0.0001\n");
  const std::string memory = message("Dense.voxelSize: 0.003\nDense.truncation: 0.006\nDense.maxDepth: 10\n");
  EXPECT_NE(memory.find("GB"), std::string::npos) << memory;
  EXPECT_NE(memory.find("Dense.truncation"), std::string::npos) << memory;
  EXPECT_NE(message("Dense.maskMargin: 300\n").find("640 x 480"), std::string::npos);
  EXPECT_EQ(message("Dense.voxelSize: 0.005\nDense.truncation: 0.02\n"), "accepted");  // fine, and it fits
}

TEST(SettingsSections, ListsEveryDenseKeyInTheKeyTables) {
  const std::string tables = config::keysMarkdown(settingsSections());
  for (const char* key : {"Dense.voxelSize", "Dense.truncation", "Dense.maskMargin", "Dense.edgeJump", "Dense.scale",
                          "Dense.frameStep", "Dense.liveEvery", "Dense.gridResolution"})
    EXPECT_NE(tables.find(std::string("`") + key + "`"), std::string::npos) << key;
}

TEST(SettingsSections, SettingsReadWithoutThemHaveNoDenseSection) {
  const config::Settings s = config::parseSettings(kCamera, "plain.yaml");
  EXPECT_THROW(s.section<dense::DenseOptions>(), core::Error);
}

}  // namespace
}  // namespace amos::run
