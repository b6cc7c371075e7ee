#include "amos/config/dynamic_section.h"

#include <gtest/gtest.h>

#include "amos/config/settings.h"
#include "amos/core/error.h"

namespace amos::config {
namespace {

TEST(DynamicSection, ReadsThePoseRefitAndSuperpixelMaskKeys) {
  YamlReader in = YamlReader::fromText(
      "Dynamic.Reprojection.refitPose: 0\n"
      "Dynamic.Reprojection.refitMinPoints: 40\n"
      "Dynamic.Reprojection.confirmSigmas: 4.0\n"
      "Dynamic.Reprojection.confirmThreshold: 1.5\n"
      "Dynamic.Boundary.superpixelMask: false\n",
      "test.yaml");
  dynamic::DynamicOptions o;
  ASSERT_TRUE(o.reprojection.refit_pose);
  ASSERT_TRUE(o.boundary.superpixel_mask);
  readDynamicSection(in, o);
  EXPECT_FALSE(o.reprojection.refit_pose);
  EXPECT_EQ(o.reprojection.refit_min_points, 40);
  EXPECT_DOUBLE_EQ(o.reprojection.confirm_sigmas, 4.0);
  EXPECT_DOUBLE_EQ(o.reprojection.confirm_threshold_px, 1.5);
  EXPECT_FALSE(o.boundary.superpixel_mask);
}

TEST(DynamicSection, ReadsTheMaskedExtractionKeys) {
  YamlReader in = YamlReader::fromText(
      "Dynamic.priorMaskedExtraction: 0\n"
      "Dynamic.priorMaskedExtractionCoverage: 0.25\n"
      "Dynamic.InitialPose.keyframeMaxPoints: 120\n",
      "test.yaml");
  dynamic::DynamicOptions o;
  ASSERT_TRUE(o.prior_masked_extraction);
  readDynamicSection(in, o);
  EXPECT_FALSE(o.prior_masked_extraction);
  EXPECT_DOUBLE_EQ(o.prior_masked_extraction_coverage, 0.25);
  EXPECT_EQ(o.initial_pose.keyframe_max_points, 120);
  EXPECT_NO_THROW(o.check());
}

TEST(DynamicSection, ShippedConfigsSpellTheDefaults) {
  for (const char* name : {"tum1", "tum2", "tum3", "bonn"}) {
    const Settings s = loadSettings(std::string(AMOS_SOURCE_DIR) + "/configs/" + name + ".yaml");
    const dynamic::DynamicOptions defaults;
    EXPECT_EQ(s.dynamic.reprojection.refit_pose, defaults.reprojection.refit_pose) << name;
    EXPECT_EQ(s.dynamic.reprojection.refit_min_points, defaults.reprojection.refit_min_points) << name;
    EXPECT_EQ(s.dynamic.reprojection.confirm_sigmas, defaults.reprojection.confirm_sigmas) << name;
    EXPECT_EQ(s.dynamic.reprojection.confirm_threshold_px, defaults.reprojection.confirm_threshold_px) << name;
    EXPECT_EQ(s.dynamic.boundary.superpixel_mask, defaults.boundary.superpixel_mask) << name;
  }
}

TEST(DynamicSection, InvalidValuesNameTheirKey) {
  YamlReader in = YamlReader::fromText("Dynamic.Reprojection.confirmThreshold: -1\n", "bad.yaml");
  dynamic::DynamicOptions o;
  readDynamicSection(in, o);
  try {
    o.check();
    FAIL() << "a negative threshold passed";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("Dynamic.Reprojection.confirmThreshold"), std::string::npos) << e.what();
  }
  for (const char* text : {"Dynamic.priorMaskedExtractionCoverage: 1.5\n", "Dynamic.InitialPose.keyframeMaxPoints: -3\n"}) {
    YamlReader bad = YamlReader::fromText(text, "bad.yaml");
    dynamic::DynamicOptions options;
    readDynamicSection(bad, options);
    const std::string key = std::string(text).substr(0, std::string(text).find(':'));
    try {
      options.check();
      ADD_FAILURE() << text << " passed";
    } catch (const core::Error& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace amos::config
