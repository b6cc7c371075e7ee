// amos_slam_node with a real ROS master (ros_master_fixture.h): a bag made from a synthetic sequence is played into
// the node frame by frame (the next frame once the last one's pose is out, so nothing is dropped), and the node's
// trajectory equals `run --deterministic`'s on the same frames byte for byte; the poses it published as it tracked
// are within a bound of it (they are the tracking-time poses; the trajectory has local mapping's later corrections).
#include "slam_node.h"

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <condition_variable>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "amos/io/trajectory.h"
#include "amos/rosbag/bag_index.h"
#include "amos/rosbag/test_bags.h"
#include "amos/run/sequence_run.h"
#include "amos/testing/file_text.h"
#include "node_messages.h"
#include "ros_master_fixture.h"

namespace amos::node {
namespace {

const auto* const kMaster = ::testing::AddGlobalTestEnvironment(new test::RosMaster);

namespace fs = std::filesystem;
using amos::testing::fileText;

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

// Waits (bounded) until `publisher` has `count` subscribers: the subscription's connection is made asynchronously.
void waitForSubscribers(const ros::Publisher& publisher, std::size_t count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (publisher.getNumSubscribers() < count) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << publisher.getTopic() << " has no subscriber";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// ros::AsyncSpinner with two threads, started when made: the node's callbacks run as soon as it subscribes.
struct StartedSpinner : ros::AsyncSpinner {
  StartedSpinner() : ros::AsyncSpinner(2) { start(); }
};

// A node on `options` as a test runs it: its handles, the spinner, the node and a listener on its pose topic.
struct RunningNode {
  explicit RunningNode(const NodeOptions& options)
      : slam(node, private_node, options), listener(node, private_node.resolveName("pose")) {}
  void stop() {
    slam.stop();
    spinner.stop();
  }
  ros::NodeHandle node, private_node{"~"};
  StartedSpinner spinner;
  SlamNode slam;
  PoseListener listener;
};

// Plays the bag's colour / depth pairs into the node's topics, the next once the last one's pose is out.
void playFrameByFrame(const std::string& bag, const NodeOptions& options, ros::NodeHandle& node,
                      PoseListener& listener) {
  ros::Publisher rgb = node.advertise<sensor_msgs::Image>(options.rgb_topic, 100);
  ros::Publisher depth = node.advertise<sensor_msgs::Image>(options.depth_topic, 100);
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
}

// `amos-slam run --mode geometry --deterministic` (and `extra` arguments) on `bag`, writing into `output`.
void runAmosSlam(const std::string& bag, const fs::path& output, const std::string& extra) {
  const fs::path log = output.string() + ".log";
  const std::string command =
      fmt::format("'{}' run --sequence '{}' --config '{}' --mode geometry --deterministic --models '{}' --output '{}' "
                  "{} > '{}' 2>&1",
                  AMOS_SLAM_EXE, bag, rosbag::test::kTum3, AMOS_MODELS_DIR, output.string(), extra, log.string());
  ASSERT_EQ(std::system(command.c_str()), 0) << fileText(log);
}

// Every file `run` wrote into `run_dir` is in `node_dir` too (per-frame files, manifest and report.html included),
// and the node's manifest lists it. Without the viewer module neither writes report.html.
void expectRunsFiles(const fs::path& run_dir, const fs::path& node_dir) {
  const nlohmann::json manifest = nlohmann::json::parse(fileText(node_dir / "run_manifest.json"));
  const auto listed = manifest["outputs"].get<std::vector<std::string>>();
  std::size_t compared = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(run_dir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(fs::exists(node_dir / name)) << "the node did not write " << name;
    if (name != "run_manifest.json") {
      EXPECT_NE(std::find(listed.begin(), listed.end(), name), listed.end()) << "its manifest lacks " << name;
    }
    ++compared;
  }
  EXPECT_GE(compared, 8u);  // run's main files and its manifest
}

// The JSON block report.html's page draws from (viewer/report_html.h).
nlohmann::json reportData(const fs::path& report) {
  const std::string page = fileText(report);
  const std::string open = R"(<script id="amos-report-data" type="application/json">)";
  const std::size_t begin = page.find(open);
  EXPECT_NE(begin, std::string::npos) << report << " has no data block";
  if (begin == std::string::npos) return {};
  const std::size_t end = page.find("</script>", begin);
  return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

// The node's report.html shows the frames run's shows, in the same states, with the SLAM stages' times.
void expectRunsReport(const fs::path& run_dir, const fs::path& node_dir) {
  if (!fs::exists(run_dir / "report.html")) return;  // a build without the viewer module
  const nlohmann::json run = reportData(run_dir / "report.html"), node = reportData(node_dir / "report.html");
  ASSERT_TRUE(node.contains("frames"));
  EXPECT_EQ(node["frames"]["index"], run["frames"]["index"]);
  EXPECT_EQ(node["frames"]["state"], run["frames"]["state"]);
  EXPECT_EQ(node["frames"]["keypoints"], run["frames"]["keypoints"]);
  EXPECT_EQ(node["frames"]["removed"], run["frames"]["removed"]);
  double extract_ms = 0;
  for (const auto& ms : node["frames"]["extract_ms"]) extract_ms += ms.get<double>();
  EXPECT_GT(extract_ms, 0.0);
  EXPECT_EQ(node["trajectory"].size(), run["trajectory"].size());
}

NodeOptions syntheticBagOptions() {
  NodeOptions options;
  options.settings_file = rosbag::test::kTum3;
  options.mode = "geometry";
  options.deterministic = true;
  options.rgb_topic = "/camera/rgb/image_color";
  options.depth_topic = "/camera/depth/image";
  options.camera_info_topic = "/camera/rgb/camera_info";
  return options;
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
  // `amos-slam run` itself on the same bag: the files the node must write too.
  const fs::path run_dir = scratch / "run";
  runAmosSlam(bag, run_dir, "");
  const std::string expected_text = fileText(run_dir / "trajectory.txt");
  ASSERT_FALSE(expected_text.empty());

  NodeOptions options = syntheticBagOptions();
  options.output_dir = (scratch / "out").string();
  options.cloud_rate = 5;
  RunningNode running(options);
  playFrameByFrame(bag, options, running.node, running.listener);
  running.stop();

  const NodeStats stats = running.slam.stats();
  EXPECT_EQ(stats.received, static_cast<std::size_t>(kFrames));
  EXPECT_EQ(stats.dropped, 0u);
  EXPECT_EQ(stats.processed, static_cast<std::size_t>(kFrames));
  EXPECT_EQ(fileText(fs::path(options.output_dir) / "trajectory.txt"), expected_text);
  EXPECT_EQ(fileText(fs::path(options.output_dir) / "keyframes.txt"), fileText(run_dir / "keyframes.txt"));
  EXPECT_EQ(fileText(fs::path(options.output_dir) / "trajectory_live.txt"), fileText(run_dir / "trajectory_live.txt"));
  EXPECT_TRUE(fs::exists(fs::path(options.output_dir) / "node_stats.json"));
  expectRunsFiles(run_dir, options.output_dir);
  expectRunsReport(run_dir, options.output_dir);

  const std::vector<geometry_msgs::PoseStamped> published = running.listener.poses();
  ASSERT_EQ(published.size(), expected.trajectory.size());
  for (std::size_t i = 0; i < published.size(); ++i) {
    EXPECT_EQ(rosbag::stampSeconds(published[i].header.stamp), expected.trajectory[i].timestamp);
    const Eigen::Matrix4d T = poseMatrix(published[i].pose);
    // Tracking-time against final poses: local bundle adjustment moves a keyframe's pose by well under 5 mm here.
    EXPECT_LT((T.block<3, 1>(0, 3) - expected.trajectory[i].T_wc.translation()).norm(), 0.005) << "frame " << i;
  }
}

// With ~dense the live dense cloud and the floor plan built from it are published at ~dense_rate while the node
// runs, not only at shutdown: both arrive before stop(); at shutdown it writes `run --dense`'s files.
TEST(SlamNode, DenseCloudAndGridArriveWhileRunning) {
  if (!denseMappingAvailable()) GTEST_SKIP() << "a build without the dense map (Open3D)";
  const std::string sequence = rosbag::test::syntheticSequence("node", 20);
  const fs::path scratch = testing::scratchDirForThisTest("amos_node_");
  const std::string bag = rosbag::test::writeTestBag(sequence, scratch, "played.bag");
  NodeOptions options = syntheticBagOptions();
  options.dense = true;
  options.dense_rate = 10;
  options.output_dir = (scratch / "out").string();
  RunningNode running(options);
  playFrameByFrame(bag, options, running.node, running.listener);
  // Latched: the latest one published is what a new subscriber gets.
  const auto cloud = ros::topic::waitForMessage<sensor_msgs::PointCloud2>(
      running.private_node.resolveName("dense_cloud"), running.node, ros::Duration(30));
  const auto grid = ros::topic::waitForMessage<nav_msgs::OccupancyGrid>(
      running.private_node.resolveName("occupancy_grid"), running.node, ros::Duration(30));
  running.stop();  // only now: what arrived above was published while the node ran
  ASSERT_TRUE(cloud) << "no dense cloud while running";
  EXPECT_GT(cloud->width * cloud->height, 100u);
  ASSERT_TRUE(grid) << "no occupancy grid while running";
  const OccupancyGrid back = gridFromMessage(*grid);
  EXPECT_GT(back.rows * back.cols, 0);
  EXPECT_NE(std::count(back.cells.begin(), back.cells.end(), OccupancyGrid::kFree), 0);
  // At shutdown the dense files `run --dense` writes, the same mesh byte for byte (the same frames, masks, poses).
  const fs::path run_dir = scratch / "run";
  runAmosSlam(bag, run_dir, "--dense");
  expectRunsFiles(run_dir, options.output_dir);
  EXPECT_TRUE(fs::exists(run_dir / "mesh.ply"));
  EXPECT_EQ(fileText(fs::path(options.output_dir) / "mesh.ply"), fileText(run_dir / "mesh.ply"));
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
