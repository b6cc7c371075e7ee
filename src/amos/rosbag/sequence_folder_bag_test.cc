// amos::SequenceFolder over a bag (include/amos/sequence_folder.h): the frames, time stamps and pixels the folder
// the bag was written from gives (read(i) and next()), its ground truth from a topic, and errors naming the bag.
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <rosbag/bag.h>

#include <Eigen/Geometry>
#include <filesystem>

#include "amos/rosbag/test_bags.h"
#include "amos/sequence_folder.h"

namespace amos::rosbag {
namespace {

namespace fs = std::filesystem;

void appendPoseStamped(const std::string& bag, const std::string& topic, const std::vector<StampedPose>& poses) {
  ::rosbag::Bag writer(bag, ::rosbag::bagmode::Append);
  for (const StampedPose& p : poses) {
    geometry_msgs::PoseStamped m;
    m.header.stamp = ros::Time().fromSec(p.timestamp);
    m.pose.position.x = p.T_wc(0, 3);
    m.pose.position.y = p.T_wc(1, 3);
    m.pose.position.z = p.T_wc(2, 3);
    const Eigen::Quaterniond q(Eigen::Matrix3d(p.T_wc.block<3, 3>(0, 0)));
    m.pose.orientation.x = q.x();
    m.pose.orientation.y = q.y();
    m.pose.orientation.z = q.z();
    m.pose.orientation.w = q.w();
    writer.write(topic, m.header.stamp, m);
  }
}

TEST(SequenceFolderBag, ReadsTheFramesOfItsFolder) {
  ASSERT_TRUE(bagReadingAvailable());
  const std::string sequence = test::syntheticSequence("api", 8);
  const fs::path scratch = testing::scratchDirForThisTest("amos_api_bag_");
  BagWriteOptions write;
  write.compression = "lz4";
  const std::string bag = test::writeTestBag(sequence, scratch, "sequence.bag", write);
  const SequenceFolder folder(sequence);
  SequenceFolder from_bag(bag);
  EXPECT_TRUE(from_bag.isBag());
  EXPECT_FALSE(folder.isBag());
  ASSERT_EQ(from_bag.size(), folder.size());
  EXPECT_TRUE(from_bag.groundTruthFile().empty());  // none beside the bag
  EXPECT_TRUE(from_bag.groundTruth().empty());
  for (std::size_t i = 0; i < folder.size(); ++i) {
    const std::optional<RgbdImages> next = from_bag.next();
    ASSERT_TRUE(next) << i;
    const RgbdImages expected = folder.read(i);
    EXPECT_EQ(next->timestamp, expected.timestamp) << i;
    EXPECT_EQ(cv::norm(next->bgr, expected.bgr, cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(next->depth, expected.depth, cv::NORM_INF), 0.0) << i;
    const RgbdImages backwards = from_bag.read(folder.size() - 1 - i);  // read(i) in any order
    EXPECT_EQ(cv::norm(backwards.bgr, folder.read(folder.size() - 1 - i).bgr, cv::NORM_INF), 0.0) << i;
  }
  EXPECT_FALSE(from_bag.next());
  EXPECT_EQ(from_bag.skipped(), 0u);
}

TEST(SequenceFolderBag, GroundTruthFromATopicWinsOverTheFile) {
  const std::string sequence = test::syntheticSequence("api", 8);
  const fs::path scratch = testing::scratchDirForThisTest("amos_api_bag_");
  const std::string bag = test::writeTestBag(sequence, scratch, "sequence.bag");
  const std::vector<StampedPose> truth = SequenceFolder(sequence).groundTruth();
  ASSERT_FALSE(truth.empty());
  appendPoseStamped(bag, "/mocap/pose", truth);
  fs::copy_file(fs::path(sequence) / "groundtruth.txt", scratch / "groundtruth.txt");
  EXPECT_EQ(SequenceFolder(bag).groundTruthFile(), (scratch / "groundtruth.txt").string());
  SequenceOptions options;
  options.groundtruth_topic = "/mocap/pose";
  const SequenceFolder with_topic(bag, options);
  EXPECT_TRUE(with_topic.groundTruthFile().empty());
  const std::vector<StampedPose> poses = with_topic.groundTruth();
  ASSERT_EQ(poses.size(), truth.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(poses[i].timestamp, truth[i].timestamp);
    EXPECT_LT((poses[i].T_wc - truth[i].T_wc).norm(), 1e-12);
  }
}

TEST(SequenceFolderBag, ErrorsNameTheBagAndTheTopic) {
  const std::string sequence = test::syntheticSequence("api", 8);
  const fs::path scratch = testing::scratchDirForThisTest("amos_api_bag_");
  const std::string bag = test::writeTestBag(sequence, scratch, "sequence.bag");
  SequenceOptions options;
  options.rgb_topic = "/camera/rgb/image_color";
  options.depth_topic = "/camera/depth_registered/image_raw";
  try {
    SequenceFolder folder(bag, options);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bag '" + bag + "' has no depth topic '/camera/depth_registered/image_raw'"),
              std::string::npos)
        << e.what();
  }
  const SequenceFolder folder(bag);
  EXPECT_THROW(folder.read(8), std::runtime_error);
}

}  // namespace
}  // namespace amos::rosbag
