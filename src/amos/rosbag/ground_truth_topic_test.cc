// Ground truth from a bag's topic (rosbag/ground_truth_topic.h; run --groundtruth-topic): each accepted message
// type gives groundtruth.txt's poses back, a run over the bag with the topic evaluates as with the file, and a
// missing topic, a topic of another type or a /tf without the frame pair is an error naming the bag and the topic.
#include "amos/rosbag/ground_truth_topic.h"

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <filesystem>

#include "amos/run/bag_source.h"
#include "amos/run/sequence_run.h"
#include "amos/rosbag/test_bags.h"

namespace amos::rosbag {
namespace {

namespace fs = std::filesystem;

geometry_msgs::Transform transformOf(const core::SE3& T) {
  geometry_msgs::Transform t;
  t.translation.x = T.translation().x();
  t.translation.y = T.translation().y();
  t.translation.z = T.translation().z();
  const Eigen::Quaterniond q(T.linear());
  t.rotation.x = q.x();
  t.rotation.y = q.y();
  t.rotation.z = q.z();
  t.rotation.w = q.w();
  return t;
}

geometry_msgs::Pose poseOf(const core::SE3& T) {
  const geometry_msgs::Transform t = transformOf(T);
  geometry_msgs::Pose p;
  p.position.x = t.translation.x;
  p.position.y = t.translation.y;
  p.position.z = t.translation.z;
  p.orientation = t.rotation;
  return p;
}

geometry_msgs::TransformStamped stampedTransform(const io::StampedPose& pose, const std::string& parent,
                                                 const std::string& child) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time().fromSec(pose.timestamp);
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform = transformOf(pose.T_wc);
  return t;
}

// `poses` appended to `bag` on `topic` as messages of `type` (PoseStamped, TransformStamped, Odometry, TFMessage:
// /world -> /kinect, with a second transform in each message that is not the ground truth).
void appendGroundTruth(const std::string& bag, const std::string& topic, const std::string& type,
                       const std::vector<io::StampedPose>& poses) {
  ::rosbag::Bag writer(bag, ::rosbag::bagmode::Append);
  for (const io::StampedPose& pose : poses) {
    const ros::Time stamp = ros::Time().fromSec(pose.timestamp);
    if (type == "PoseStamped") {
      geometry_msgs::PoseStamped m;
      m.header.stamp = stamp;
      m.pose = poseOf(pose.T_wc);
      writer.write(topic, stamp, m);
    } else if (type == "TransformStamped") {
      writer.write(topic, stamp, stampedTransform(pose, "world", "kinect"));
    } else if (type == "Odometry") {
      nav_msgs::Odometry m;
      m.header.stamp = stamp;
      m.pose.pose = poseOf(pose.T_wc);
      writer.write(topic, stamp, m);
    } else {
      tf2_msgs::TFMessage m;
      m.transforms.push_back(stampedTransform(pose, "/kinect", "/openni_camera"));
      m.transforms.push_back(stampedTransform(pose, "/world", "/kinect"));
      writer.write(topic, stamp, m);
    }
  }
}

std::vector<io::StampedPose> groundTruthOf(const std::string& sequence) {
  return io::readTumTrajectoryWithPoses(sequence + "/groundtruth.txt", "ground-truth file");
}

void expectSamePoses(const std::vector<io::StampedPose>& a, const std::vector<io::StampedPose>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].timestamp, b[i].timestamp) << i;
    EXPECT_LT((a[i].T_wc.matrix() - b[i].T_wc.matrix()).norm(), 1e-12) << i;
  }
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(GroundTruthTopic, EachMessageTypeGivesGroundtruthTxtsPoses) {
  const std::string sequence = test::syntheticSequence("groundtruth", 10);
  const std::vector<io::StampedPose> truth = groundTruthOf(sequence);
  const fs::path scratch = testing::scratchDirForThisTest("amos_bag_gt_");
  for (const std::string type : {"PoseStamped", "TransformStamped", "Odometry", "TFMessage"}) {
    SCOPED_TRACE(type);
    const std::string bag = test::writeTestBag(sequence, scratch, type + ".bag");
    const std::string topic = type == "TFMessage" ? "/tf" : "/groundtruth";
    appendGroundTruth(bag, topic, type, truth);
    expectSamePoses(readGroundTruthTopic(bag, {topic}), truth);
  }
}

TEST(GroundTruthTopic, ErrorsNameTheBagAndTheTopic) {
  const std::string sequence = test::syntheticSequence("groundtruth", 10);
  const fs::path scratch = testing::scratchDirForThisTest("amos_bag_gt_");
  const std::string bag = test::writeTestBag(sequence, scratch, "tf.bag");
  appendGroundTruth(bag, "/tf", "TFMessage", groundTruthOf(sequence));
  const std::string missing = errorOf([&] { readGroundTruthTopic(bag, {"/vicon"}); });
  EXPECT_NE(missing.find("bag '" + bag + "' has no ground-truth topic '/vicon'"), std::string::npos) << missing;
  const std::string wrong_type = errorOf([&] { readGroundTruthTopic(bag, {"/camera/rgb/camera_info"}); });
  EXPECT_NE(wrong_type.find("ground-truth topic '/camera/rgb/camera_info' holds sensor_msgs/CameraInfo"),
            std::string::npos)
      << wrong_type;
  const std::string no_pair = errorOf([&] { readGroundTruthTopic(bag, {"/tf", "/map", "/camera"}); });
  EXPECT_NE(no_pair.find("topic '/tf' has no pose from '/map' to '/camera' (its transforms: "), std::string::npos)
      << no_pair;
  EXPECT_NE(no_pair.find("world -> kinect"), std::string::npos) << no_pair;
}

// The topic wins over a groundtruth.txt beside the bag, and evaluates as the file does.
TEST(GroundTruthTopic, RunWithTheTopicReportsTheFilesAte) {
  const std::string sequence = test::syntheticSequence("groundtruth", 10);
  const fs::path scratch = testing::scratchDirForThisTest("amos_bag_gt_");
  const std::string bag = test::writeTestBag(sequence, scratch, "tf.bag");
  std::vector<io::StampedPose> truth = groundTruthOf(sequence);
  appendGroundTruth(bag, "/tf", "TFMessage", truth);
  // A groundtruth.txt beside the bag that is not the sequence's: the topic must win over it.
  for (io::StampedPose& p : truth) p.T_wc.translation().x() += 0.5 * p.timestamp - 0.5 * truth.front().timestamp;
  io::writeTumTrajectory((scratch / "groundtruth.txt").string(), truth);
  run::SequenceRunOptions options;
  options.source = run::FrameSourceKind::kBag;
  options.sequence_dir = bag;
  options.mode = "geometry";
  options.deterministic = true;
  options.groundtruth_topic = "/tf";
  const run::SequenceRunResult with_topic = run::runSequence(run::loadBagSettings(test::kTum3, options), options);
  run::SequenceRunOptions folder = options;
  folder.source = run::FrameSourceKind::kFolder;
  folder.sequence_dir = sequence;
  folder.groundtruth_topic.clear();
  const run::SequenceRunResult with_file = run::runSequence(config::loadSettings(test::kTum3), folder);
  ASSERT_TRUE(with_topic.info.evaluation);
  ASSERT_TRUE(with_file.info.evaluation);
  EXPECT_NEAR(with_topic.info.evaluation->ate_rmse_m, with_file.info.evaluation->ate_rmse_m, 1e-12);
  EXPECT_EQ(with_topic.info.evaluation->ate_pairs, with_file.info.evaluation->ate_pairs);
}

}  // namespace
}  // namespace amos::rosbag
