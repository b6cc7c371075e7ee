// The topics read from a bag: the known drivers' names, the requested ones, and errors naming bag and topic.
#include "amos/rosbag/bag_topics.h"

#include <gtest/gtest.h>

#include "amos/testing/error_of.h"

namespace amos::rosbag {
namespace {

TEST(BagTopics, TumNamesWithTheirCameraInfo) {
  const BagTopics t = chooseTopics({"/camera/depth/image", "/camera/rgb/camera_info", "/camera/rgb/image_color", "/tf"},
                                   {}, "x.bag");
  EXPECT_EQ(t.rgb, "/camera/rgb/image_color");
  EXPECT_EQ(t.depth, "/camera/depth/image");
  EXPECT_EQ(t.camera_info, "/camera/rgb/camera_info");
}

TEST(BagTopics, RealSenseAlignedDepthWithoutCameraInfo) {
  const BagTopics t =
      chooseTopics({"/camera/aligned_depth_to_color/image_raw", "/camera/color/image_raw"}, {}, "x.bag");
  EXPECT_EQ(t.rgb, "/camera/color/image_raw");
  EXPECT_EQ(t.depth, "/camera/aligned_depth_to_color/image_raw");
  EXPECT_EQ(t.camera_info, "");
}

TEST(BagTopics, RequestedTopicsWin) {
  const BagTopics t = chooseTopics({"/a", "/b", "/camera/depth/image", "/camera/rgb/image_color"}, {"/a", "/b", ""},
                                   "x.bag");
  EXPECT_EQ(t.rgb, "/a");
  EXPECT_EQ(t.depth, "/b");
}

TEST(BagTopics, ErrorsNameTheBagAndTheTopic) {
  const std::string unknown = testing::errorOf([] { chooseTopics({"/a", "/b"}, {}, "rec.bag"); });
  EXPECT_NE(unknown.find("rec.bag"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("/a, /b"), std::string::npos) << unknown;
  const std::string missing =
      testing::errorOf([] { chooseTopics({"/a", "/b"}, {"/a", "/depth", ""}, "rec.bag"); });
  EXPECT_NE(missing.find("rec.bag"), std::string::npos) << missing;
  EXPECT_NE(missing.find("depth topic '/depth'"), std::string::npos) << missing;
}

}  // namespace
}  // namespace amos::rosbag
