#include "amos/config/dynamic_section.h"

#include <gtest/gtest.h>

#include "amos/config/settings.h"
#include "amos/core/error.h"

namespace amos::config {
namespace {

const std::string kCamera = "Camera.fx: 500\nCamera.fy: 500\nCamera.cx: 320\nCamera.cy: 240\n";

TEST(DynamicSection, ReadsThePoseRefitAndSuperpixelMaskKeys) {
  const Settings s = parseSettings(kCamera +
                                       "Dynamic.Reprojection.refitPose: 0\n"
                                       "Dynamic.Reprojection.refitMinPoints: 40\n"
                                       "Dynamic.Reprojection.confirmSigmas: 4.0\n"
                                       "Dynamic.Reprojection.confirmThreshold: 1.5\n"
                                       "Dynamic.Boundary.superpixelMask: false\n",
                                   "test.yaml");
  const dynamic::DynamicOptions& o = s.dynamic;
  EXPECT_FALSE(o.reprojection.refit_pose);
  EXPECT_EQ(o.reprojection.refit_min_points, 40);
  EXPECT_DOUBLE_EQ(o.reprojection.confirm_sigmas, 4.0);
  EXPECT_DOUBLE_EQ(o.reprojection.confirm_threshold_px, 1.5);
  EXPECT_FALSE(o.boundary.superpixel_mask);
}

TEST(DynamicSection, ReadsTheMaskedExtractionKeys) {
  const Settings s = parseSettings(kCamera +
                                       "Dynamic.priorMaskedExtraction: 0\n"
                                       "Dynamic.priorMaskedExtractionCoverage: 0.25\n"
                                       "Dynamic.InitialPose.keyframeMaxPoints: 120\n",
                                   "test.yaml");
  EXPECT_FALSE(s.dynamic.prior_masked_extraction);
  EXPECT_DOUBLE_EQ(s.dynamic.prior_masked_extraction_coverage, 0.25);
  EXPECT_EQ(s.dynamic.initial_pose.keyframe_max_points, 120);
}

// Named by the option headers and by the validation messages, but never read before: a user who set them was told
// the key is unknown.
TEST(DynamicSection, ReadsTheEpipolarIterationsAndTheLkEpsilon) {
  const Settings s =
      parseSettings(kCamera + "Dynamic.Epipolar.maxIterations: 500\nDynamic.LK.epsilon: 0.05\n", "test.yaml");
  EXPECT_EQ(s.dynamic.epipolar.max_iterations, 500);
  EXPECT_DOUBLE_EQ(s.dynamic.tracking.lk_epsilon, 0.05);
}

TEST(DynamicSection, ReadsTheModeByName) {
  EXPECT_EQ(parseSettings(kCamera + "Dynamic.mode: geometry\n", "t.yaml").dynamic.mode,
            dynamic::DynamicMode::kGeometry);
  try {
    parseSettings(kCamera + "Dynamic.mode: everything\n", "t.yaml");
    FAIL() << "an unknown mode passed";
  } catch (const core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.yaml:5: key 'Dynamic.mode' must be one of none, prior, geometry, full, "
                                         "got 'everything'"),
              std::string::npos)
        << e.what();
  }
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

TEST(DynamicSection, InvalidValuesNameTheirKeyAndLine) {
  for (const char* line :
       {"Dynamic.Reprojection.confirmThreshold: -1\n", "Dynamic.priorMaskedExtractionCoverage: 1.5\n",
        "Dynamic.InitialPose.keyframeMaxPoints: -3\n"}) {
    const std::string key = std::string(line).substr(0, std::string(line).find(':'));
    try {
      parseSettings(kCamera + line, "bad.yaml");
      ADD_FAILURE() << line << " passed";
    } catch (const core::Error& e) {
      EXPECT_NE(std::string(e.what()).find("bad.yaml:5: " + key + " "), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace amos::config
