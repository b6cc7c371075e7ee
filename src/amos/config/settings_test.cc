#include "amos/config/settings.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "amos/config/yaml_reader.h"
#include "amos/core/error.h"

namespace amos::config {
namespace {

const char* kMinimal =
    "%YAML:1.0\n"
    "Camera.fx: 500.0\n"
    "Camera.fy: 500.0\n"
    "Camera.cx: 320.0\n"
    "Camera.cy: 240.0\n";

std::string errorOf(const std::string& text) {
  try {
    parseSettings(text, "test.yaml");
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

TEST(Settings, ShippedConfigsParseWithTheirCalibration) {
  const std::string dir = std::string(AMOS_SOURCE_DIR) + "/configs/";
  const Settings tum2 = loadSettings(dir + "tum2.yaml");
  EXPECT_DOUBLE_EQ(tum2.camera.fx, 520.908620);
  EXPECT_DOUBLE_EQ(tum2.camera.k3, 0.917205);
  EXPECT_DOUBLE_EQ(tum2.depth_factor, 5208.0);
  EXPECT_EQ(tum2.orb.num_features, 2000);
  EXPECT_NEAR(tum2.closeDepthThreshold(), 40.0 * 40.0 / 520.908620, 1e-12);
  const Settings bonn = loadSettings(dir + "bonn.yaml");
  EXPECT_DOUBLE_EQ(bonn.camera.cy, 237.756098);
  EXPECT_EQ(bonn.groundtruth_format, GroundTruthFormat::kBonn);
  EXPECT_EQ(loadSettings(dir + "tum1.yaml").camera.width, 640);
  EXPECT_FALSE(loadSettings(dir + "tum3.yaml").camera.hasDistortion());
}

TEST(Settings, DefaultsFillWhatTheFileOmits) {
  const Settings s = parseSettings(kMinimal, "test.yaml");
  EXPECT_EQ(s.orb.num_levels, 8);
  EXPECT_DOUBLE_EQ(s.depth_factor, 5000.0);
  EXPECT_EQ(s.readerOptions().width, 640);
}

TEST(Settings, WrongTypeNamesFileLineAndKey) {
  const std::string e = errorOf(std::string(kMinimal) + "ORBextractor.nLevels: eight\n");
  EXPECT_NE(e.find("test.yaml:6"), std::string::npos) << e;
  EXPECT_NE(e.find("ORBextractor.nLevels"), std::string::npos) << e;
}

TEST(Settings, InvalidValueNamesFileLineAndKey) {
  const std::string e = errorOf(std::string(kMinimal) + "DepthMapFactor: -1\n");
  EXPECT_NE(e.find("test.yaml:6"), std::string::npos) << e;
  EXPECT_NE(e.find("DepthMapFactor"), std::string::npos) << e;
  const std::string orb = errorOf(std::string(kMinimal) + "ORBextractor.nFeatures: 0\n");
  EXPECT_NE(orb.find("ORBextractor.nFeatures"), std::string::npos) << orb;
  EXPECT_NE(orb.find("test.yaml:6"), std::string::npos) << orb;
}

TEST(Settings, TheCameraKeysHaveTheBoundsTheirMeaningGives) {
  for (const auto& [line, key] : std::vector<std::pair<std::string, std::string>>{
           {"Camera.fps: 100000\n", "Camera.fps"},
           {"Camera.bf: 5000\n", "Camera.bf"},  // a 10 m baseline at fx 500
           {"ThDepth: 100000\n", "ThDepth"},
           {"DepthMapFactor: 1\n", "DepthMapFactor"},
           {"DepthMapFactor: 100000\n", "DepthMapFactor"}}) {
    const std::string e = errorOf(std::string(kMinimal) + line);
    EXPECT_NE(e.find("test.yaml:6: " + key), std::string::npos) << line << e;
  }
  EXPECT_EQ(errorOf(std::string(kMinimal) + "Camera.fps: 60\nCamera.bf: 40\nThDepth: 40\nDepthMapFactor: 1000\n"), "");
}

TEST(Settings, MissingRequiredKeyIsAnError) {
  const std::string e = errorOf("Camera.fx: 500.0\nCamera.fy: 500.0\nCamera.cx: 320.0\n");
  EXPECT_NE(e.find("Camera.cy"), std::string::npos) << e;
}

TEST(Settings, MalformedYamlNamesTheLine) {
  const std::string e = errorOf(std::string(kMinimal) + "Camera.k1: [0.1, \n  : :\n");
  EXPECT_NE(e.find("test.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed"), std::string::npos) << e;
}

TEST(Settings, BadEnumValueIsNamed) {
  const std::string e = errorOf(std::string(kMinimal) + "Dataset.groundtruth: vicon\n");
  EXPECT_NE(e.find("Dataset.groundtruth"), std::string::npos) << e;
}

TEST(Settings, SlamSectionsReachTheirOptionStructs) {
  const Settings s = parseSettings(std::string(kMinimal) +
                                       "Camera.fps: 15.0\n"
                                       "Tracking.localMinInliers: 40\n"
                                       "Tracking.externalPose: replace\n"
                                       "Matching.thLow: 45\n"
                                       "Relocalization.minInliers: 60\n"
                                       "Mapping.covisibilityMinWeight: 20\n"
                                       "Mapping.fuseRadius: 4.5\n"
                                       "LocalBA.enabled: 0\n"
                                       "LocalBA.iterationsRefine: 3\n",
                                   "test.yaml");
  EXPECT_EQ(s.tracking.max_frames_between_keyframes, 15);  // follows Camera.fps
  EXPECT_EQ(s.tracking.local_min_inliers, 40);
  EXPECT_EQ(s.tracking.external_pose, tracking::ExternalPosePolicy::kReplace);
  EXPECT_EQ(s.tracking.matching.th_low, 45);
  EXPECT_EQ(s.tracking.relocalization.min_inliers, 60);
  EXPECT_EQ(s.covisibility.min_weight, 20);
  EXPECT_DOUBLE_EQ(s.mapping.fusion.radius, 4.5);
  EXPECT_FALSE(s.mapping.local_ba);
  EXPECT_EQ(s.mapping.ba.iterations_refine, 3);
  EXPECT_EQ(parseSettings(std::string(kMinimal) + "Tracking.maxFrames: 12\n", "t.yaml")
                .tracking.max_frames_between_keyframes, 12);
}

// ORB-SLAM2's close-point counts (100 / 70) are for 1000 features; they follow ORBextractor.nFeatures unless set.
TEST(Settings, CloseCountsFollowTheFeatureCountUnlessSet) {
  const Settings twice = parseSettings(std::string(kMinimal) + "ORBextractor.nFeatures: 2000\n", "t.yaml");
  EXPECT_EQ(twice.tracking.close_tracked_max, 200);
  EXPECT_EQ(twice.tracking.close_untracked_min, 140);
  const Settings orb = parseSettings(std::string(kMinimal) + "ORBextractor.nFeatures: 1000\n", "t.yaml");
  EXPECT_EQ(orb.tracking.close_tracked_max, 100);
  EXPECT_EQ(orb.tracking.close_untracked_min, 70);
  const Settings set = parseSettings(std::string(kMinimal) +
                                         "ORBextractor.nFeatures: 2000\nTracking.closeTrackedMax: 120\n"
                                         "Tracking.closeUntrackedMin: 90\n",
                                     "t.yaml");
  EXPECT_EQ(set.tracking.close_tracked_max, 120);
  EXPECT_EQ(set.tracking.close_untracked_min, 90);
}

TEST(Settings, InvalidSlamValueNamesFileLineAndKey) {
  const std::string e = errorOf(std::string(kMinimal) + "Tracking.localMinInliers: 2\n");
  EXPECT_NE(e.find("test.yaml:6"), std::string::npos) << e;
  EXPECT_NE(e.find("Tracking.localMinInliers"), std::string::npos) << e;
  EXPECT_NE(errorOf(std::string(kMinimal) + "Tracking.externalPose: sometimes\n").find("test.yaml:6"),
            std::string::npos);
}

TEST(YamlReader, ReportsUnknownKeys) {
  YamlReader in = YamlReader::fromText(std::string(kMinimal) + "Camera.fz: 3\n", "t.yaml");
  double fx = 0;
  in.read("Camera.fx", fx);
  const auto unread = in.unreadKeys();
  EXPECT_NE(std::find(unread.begin(), unread.end(), "Camera.fz"), unread.end());
  EXPECT_EQ(in.where("Camera.fz"), "t.yaml:6");
}

TEST(YamlReader, AKeySetTwiceIsAnErrorNamingBothLines) {
  // The last value used to win silently: a second Camera.fx moved fr2's ATE from 4.3 to 10.3 mm.
  const std::string e = errorOf(std::string(kMinimal) + "ORBextractor.nFeatures: 900\nCamera.fx: 525.0\n");
  EXPECT_NE(e.find("test.yaml:7: key 'Camera.fx' is set again (first on line 2)"), std::string::npos) << e;
  EXPECT_NE(errorOf(std::string(kMinimal) + "\"Camera.fy\": 1\n").find("test.yaml:6: key 'Camera.fy'"),
            std::string::npos);
  EXPECT_NE(errorOf(std::string(kMinimal) + "? [a, b]\n: 1\n").find("test.yaml:6: a key must be a plain name"),
            std::string::npos);
}

TEST(YamlReader, MissingFileIsAnError) {
  EXPECT_THROW(YamlReader::fromFile("/nonexistent/settings.yaml"), core::Error);
}

}  // namespace
}  // namespace amos::config
