// Bags that cannot be tracked: each is an error naming the bag (and the topic) before any frame is read.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

#include <filesystem>
#include <fstream>

#include "amos/rosbag/bag_index.h"
#include "amos/rosbag/bag_settings.h"
#include "amos/rosbag/image_messages.h"
#include "amos/rosbag/test_bags.h"
#include "amos/testing/error_of.h"

namespace amos::rosbag {
namespace {

namespace fs = std::filesystem;

void expectMentions(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
}

// A bag with one colour and one depth message per stamp, of the given encodings.
std::string bagWithEncodings(const fs::path& dir, const std::string& colour_encoding, int colour_type,
                             const std::string& depth_encoding, int depth_type) {
  const std::string bag = (dir / "encodings.bag").string();
  ::rosbag::Bag writer(bag, ::rosbag::bagmode::Write);
  for (int i = 1; i <= 3; ++i) {
    const ros::Time stamp(100 + i, 0);
    writer.write("/camera/rgb/image_color", stamp,
                 imageMessage(cv::Mat(480, 640, colour_type, cv::Scalar::all(80)), colour_encoding, stamp, "c"));
    writer.write("/camera/depth/image", stamp,
                 imageMessage(cv::Mat(480, 640, depth_type, cv::Scalar::all(1)), depth_encoding, stamp, "c"));
  }
  writer.close();
  return bag;
}

TEST(BadBag, TruncatedBagIsAnErrorNamingIt) {
  const std::string sequence = test::syntheticSequence("bad", 4);
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  const std::string bag = test::writeTestBag(sequence, dir, "whole.bag");
  const std::string truncated = (dir / "truncated.bag").string();
  fs::copy_file(bag, truncated);
  fs::resize_file(truncated, fs::file_size(bag) / 2);
  expectMentions(testing::errorOf([&] { indexBag(truncated); }), {"bag '" + truncated + "'"});
}

TEST(BadBag, FileThatIsNoBagIsAnErrorNamingIt) {
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  const std::string bag = (dir / "text.bag").string();
  std::ofstream(bag) << "not a bag\n";
  expectMentions(testing::errorOf([&] { indexBag(bag); }), {"bag '" + bag + "' cannot be read"});
}

TEST(BadBag, WrongTopicsAreAnErrorNamingBagAndTopic) {
  const std::string sequence = test::syntheticSequence("bad", 4);
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  BagWriteOptions write;
  write.topics = {"/left/image", "/left/depth", "/left/camera_info"};
  const std::string bag = test::writeTestBag(sequence, dir, "other_topics.bag", write);
  expectMentions(testing::errorOf([&] { indexBag(bag); }), {bag, "/left/depth", "/left/image", "known"});
  BagOptions requested;
  requested.topics = {"/left/image", "/right/depth", ""};
  expectMentions(testing::errorOf([&] { indexBag(bag, requested); }), {bag, "depth topic '/right/depth'"});
  requested.topics = {"/left/image", "/left/depth", ""};
  EXPECT_EQ(indexBag(bag, requested).sequence.frames.size(), 4u);  // named, they are read
}

TEST(BadBag, ColourOfAnotherEncodingIsAnErrorNamingBagTopicAndEncoding) {
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  const std::string bag = bagWithEncodings(dir, "bayer_rggb8", CV_8UC1, "16UC1", CV_16UC1);
  expectMentions(testing::errorOf([&] { indexBag(bag); }), {bag, "/camera/rgb/image_color", "'bayer_rggb8'"});
}

TEST(BadBag, DepthOfAnotherEncodingIsAnErrorNamingBagTopicAndEncoding) {
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  const std::string bag = bagWithEncodings(dir, "rgb8", CV_8UC3, "8UC1", CV_8UC1);
  expectMentions(testing::errorOf([&] { indexBag(bag); }), {bag, "/camera/depth/image", "'8UC1'"});
  EXPECT_EQ(indexBag(bagWithEncodings(dir, "rgb8", CV_8UC3, "16UC1", CV_16UC1)).sequence.frames.size(), 3u);
}

TEST(BadBag, TopicOfAnotherMessageTypeIsAnErrorNamingIt) {
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  const std::string bag = (dir / "types.bag").string();
  {
    ::rosbag::Bag writer(bag, ::rosbag::bagmode::Write);
    const ros::Time stamp(100, 0);
    writer.write("/camera/rgb/image_color", stamp, sensor_msgs::CameraInfo());
    writer.write("/camera/depth/image", stamp, imageMessage(cv::Mat(4, 4, CV_16UC1), "16UC1", stamp, "c"));
  }
  expectMentions(testing::errorOf([&] { indexBag(bag); }),
                 {bag, "/camera/rgb/image_color", "sensor_msgs/CameraInfo", "expected sensor_msgs/Image"});
}

// The calibration: from camera_info when the settings leave it out; the settings' when they have it; an error
// naming the bag when neither has it.
TEST(BagSettings, CameraInfoFillsTheCalibrationTheSettingsLeaveOut) {
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  const std::string no_camera = (dir / "no_camera.yaml").string();
  std::ofstream(no_camera) << "%YAML:1.0\nDepthMapFactor: 5000.0\n";
  core::CameraIntrinsics info = test::syntheticCamera();
  info.fx = 500.25;
  const config::Settings filled = settingsForBag(no_camera, info, "bag 'x.bag', topic '/info'");
  EXPECT_EQ(filled.camera.fx, 500.25);
  EXPECT_EQ(filled.camera.cy, info.cy);
  const config::Settings own = settingsForBag(test::kTum3, info, "bag 'x.bag', topic '/info'");
  EXPECT_EQ(own.camera.fx, config::loadSettings(test::kTum3).camera.fx);  // the settings win
  expectMentions(testing::errorOf([&] { settingsForBag(no_camera, std::nullopt, "bag 'x.bag'"); }),
                 {"bag 'x.bag'", "no camera_info", no_camera});
}

TEST(BagSettings, BagWithoutCameraInfoHasNone) {
  const std::string sequence = test::syntheticSequence("bad", 4);
  const fs::path dir = testing::scratchDirForThisTest("amos_bag_");
  BagWriteOptions write;
  write.camera = std::nullopt;
  write.topics.camera_info = "";
  BagWriteOptions no_info = write;
  const std::string bag = (dir / "no_info.bag").string();
  writeBag(io::indexSequence(sequence), bag, no_info);
  const BagIndex index = indexBag(bag);
  EXPECT_EQ(index.topics.camera_info, "");
  EXPECT_FALSE(index.camera_info);
}

}  // namespace
}  // namespace amos::rosbag
