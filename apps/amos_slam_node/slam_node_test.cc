// amos_slam_node with a real ROS master (ros_master_fixture.h): a bag made from a synthetic sequence is played into
// the node frame by frame (the next frame once the last one's pose is out, so nothing is dropped), and the node's
// trajectory equals `run --deterministic`'s on the same frames byte for byte; the poses it published as it tracked
// are within a bound of it (they are the tracking-time poses; the trajectory has local mapping's later corrections).
#include "slam_node.h"

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <condition_variable>
#include <fstream>
#include <mutex>
#include <sstream>

#include "amos/io/trajectory.h"
#include "amos/report/run_report.h"
#include "amos/rosbag/bag_index.h"
#include "amos/rosbag/test_bags.h"
#include "amos/run/sequence_run.h"
#include "node_messages.h"
#include "ros_master_fixture.h"

namespace amos::node {
namespace {

const auto* const kMaster = ::testing::AddGlobalTestEnvironment(new test::RosMaster);

namespace fs = std::filesystem;

// The poses published on a topic, with a wait for the n-th.
class PoseListener {
 public:
  PoseListener(ros::NodeHandle& node, const std::string& topic)
      : subscriber_(node.subscribe(topic, 100, &PoseListener::onPose, this)) {}

  bool waitFor(std::size_t count) {
    std::unique_lock lock(mutex_);
    return arrived_.wait_for(lock, std::chrono::seconds(60), [&] { return poses_.size() >= count; });
  }
  std::vector<geometry_msgs::PoseStamped> poses() const {
    std::lock_guard lock(mutex_);
    return poses_;
  }

 private:
  void onPose(const geometry_msgs::PoseStampedConstPtr& pose) {
    {
      std::lock_guard lock(mutex_);
      poses_.push_back(*pose);
    }
    arrived_.notify_all();
  }

  ros::Subscriber subscriber_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<geometry_msgs::PoseStamped> poses_;
};

std::string fileText(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Waits (bounded) until `publisher` has `count` subscribers: the subscription's connection is made asynchronously.
void waitForSubscribers(const ros::Publisher& publisher, std::size_t count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (publisher.getNumSubscribers() < count) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << publisher.getTopic() << " has no subscriber";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

TEST(SlamNode, PlayedBagGivesRunsTrajectory) {
  constexpr int kFrames = 20;
  const std::string sequence = rosbag::test::syntheticSequence("node", kFrames);
  const fs::path scratch = testing::scratchDirForThisTest("amos_node_");
  const std::string bag = rosbag::test::writeTestBag(sequence, scratch, "played.bag");

  run::SequenceRunOptions reference;
  reference.sequence_dir = sequence;
  reference.mode = "geometry";
  reference.deterministic = true;
  const run::SequenceRunResult expected = run::runSequence(config::loadSettings(rosbag::test::kTum3), reference);
  report::writeRunOutputs((scratch / "run").string(), expected.slam(), expected.info);  // as `run` writes them
  const std::string expected_text = fileText(scratch / "run" / "trajectory.txt");
  ASSERT_FALSE(expected_text.empty());

  NodeOptions options;
  options.settings_file = rosbag::test::kTum3;
  options.mode = "geometry";
  options.deterministic = true;
  options.rgb_topic = "/camera/rgb/image_color";
  options.depth_topic = "/camera/depth/image";
  options.camera_info_topic = "/camera/rgb/camera_info";
  options.output_dir = (scratch / "out").string();
  options.cloud_rate = 5;
  ros::NodeHandle node, private_node("~");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  SlamNode slam_node(node, private_node, options);
  PoseListener listener(node, private_node.resolveName("pose"));
  ros::Publisher rgb = node.advertise<sensor_msgs::Image>(options.rgb_topic, kFrames);
  ros::Publisher depth = node.advertise<sensor_msgs::Image>(options.depth_topic, kFrames);
  waitForSubscribers(rgb, 1);
  waitForSubscribers(depth, 1);

  const rosbag::BagIndex index = rosbag::indexBag(bag);
  ::rosbag::Bag reader(bag);
  std::vector<sensor_msgs::ImageConstPtr> colour, depths;
  for (const ::rosbag::MessageInstance& m : ::rosbag::View(reader)) {
    if (m.getTopic() == options.rgb_topic) colour.push_back(m.instantiate<sensor_msgs::Image>());
    if (m.getTopic() == options.depth_topic) depths.push_back(m.instantiate<sensor_msgs::Image>());
  }
  for (std::size_t i = 0; i < index.messages.size(); ++i) {
    rgb.publish(colour[index.messages[i].first]);
    depth.publish(depths[index.messages[i].second]);
    ASSERT_TRUE(listener.waitFor(i + 1)) << "no pose for frame " << i;
  }
  slam_node.stop();
  spinner.stop();

  const NodeStats stats = slam_node.stats();
  EXPECT_EQ(stats.received, static_cast<std::size_t>(kFrames));
  EXPECT_EQ(stats.dropped, 0u);
  EXPECT_EQ(stats.processed, static_cast<std::size_t>(kFrames));
  EXPECT_EQ(fileText(fs::path(options.output_dir) / "trajectory.txt"), expected_text);
  EXPECT_TRUE(fs::exists(fs::path(options.output_dir) / "node_stats.json"));

  const std::vector<geometry_msgs::PoseStamped> published = listener.poses();
  ASSERT_EQ(published.size(), expected.trajectory.size());
  for (std::size_t i = 0; i < published.size(); ++i) {
    EXPECT_EQ(rosbag::stampSeconds(published[i].header.stamp), expected.trajectory[i].timestamp);
    const Eigen::Matrix4d T = poseMatrix(published[i].pose);
    // Tracking-time against final poses: local bundle adjustment moves a keyframe's pose by well under 5 mm here.
    EXPECT_LT((T.block<3, 1>(0, 3) - expected.trajectory[i].T_wc.translation()).norm(), 0.005) << "frame " << i;
  }
}

TEST(SlamNode, OccupancyGridRoundTripsThroughItsMessage) {
  OccupancyGrid grid;
  grid.rows = 3;
  grid.cols = 4;
  grid.resolution = 0.05;
  grid.cells = {0, 254, 205, 0, 254, 254, 254, 205, 205, 0, 0, 254};
  grid.origin = Eigen::Vector2d(-1.5, 0.25);
  grid.T_mw.block<3, 1>(0, 3) = Eigen::Vector3d(0.1, -0.2, 1.2);
  const nav_msgs::OccupancyGrid message = gridMessage(grid, ros::Time(5, 0), "map");
  // The message's first row is the grid's last (bottom) row: 205, 0, 0, 254 = unknown, occupied, occupied, free.
  EXPECT_EQ(message.data[0], -1);
  EXPECT_EQ(message.data[1], 100);
  EXPECT_EQ(message.data[3], 0);
  const OccupancyGrid back = gridFromMessage(message);
  EXPECT_EQ(back.rows, grid.rows);
  EXPECT_EQ(back.cols, grid.cols);
  EXPECT_EQ(back.cells, grid.cells);
  EXPECT_FLOAT_EQ(static_cast<float>(back.resolution), static_cast<float>(grid.resolution));
  // The lower-left corner lands on the same place in the world.
  const Eigen::Vector4d corner_map(grid.origin.x(), grid.origin.y(), 0, 1);
  const Eigen::Vector4d world = grid.T_mw.inverse() * corner_map;
  const Eigen::Vector4d world_back = back.T_mw.inverse() * Eigen::Vector4d(0, 0, 0, 1);
  EXPECT_LT((world - world_back).norm(), 1e-9);
}

TEST(SlamNode, GridPublishedThroughTheMasterArrivesWhole) {
  OccupancyGrid grid;
  grid.rows = 2;
  grid.cols = 2;
  grid.cells = {0, 254, 205, 254};
  ros::NodeHandle node;
  ros::Publisher publisher = node.advertise<nav_msgs::OccupancyGrid>("/amos_test_grid", 1, /*latch=*/true);
  publisher.publish(gridMessage(grid, ros::Time(1, 0), "map"));
  const auto received = ros::topic::waitForMessage<nav_msgs::OccupancyGrid>("/amos_test_grid", node, ros::Duration(20));
  ASSERT_TRUE(received);
  EXPECT_EQ(gridFromMessage(*received).cells, grid.cells);
}

TEST(NodeOptions, WrongValuesNameTheParameter) {
  NodeOptions o;
  o.settings_file = "x.yaml";
  o.mode = "fast";
  try {
    o.check();
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("~mode 'fast'"), std::string::npos) << e.what();
  }
}

TEST(LatestFrame, NewerFrameReplacesTheWaitingOneAndCountsItDropped) {
  LatestFrame slot;
  for (int i = 0; i < 3; ++i) {
    StampedFrame f;
    f.timestamp = i;
    slot.put(f);
  }
  const auto taken = slot.take();
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->timestamp, 2);
  EXPECT_EQ(slot.received(), 3u);
  EXPECT_EQ(slot.dropped(), 2u);
  slot.close();
  EXPECT_FALSE(slot.take());
}

}  // namespace
}  // namespace amos::node
