#include "slam_node.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>

#include "amos/rosbag/bag_index.h"
#include "amos/rosbag/bag_settings.h"
#include "amos/rosbag/image_messages.h"
#include "node_messages.h"
#include "node_stats.h"
#include "stamp_pairer.h"

namespace amos::node {

namespace fs = std::filesystem;

namespace {
// What the node writes with ~dense at shutdown beside Slam::writeOutputs' files (run --dense's dense files).
const std::vector<std::string> kDenseFiles = {"mesh.ply", "cloud.ply", "removed_points.ply", "occupancy.pgm",
                                              "occupancy.yaml"};
}  // namespace

struct SlamNode::Subscriptions {
  StampPairer pairer;
  ros::Subscriber rgb, depth, camera_info;
  tf2_ros::TransformBroadcaster broadcaster;
  tf2_ros::Buffer tf_buffer;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener;  // only with ~odom_frame

  explicit Subscriptions(const NodeOptions& o) : pairer(static_cast<std::size_t>(o.sync_queue), o.max_pair_dt) {
    if (!o.odom_frame.empty()) tf_listener = std::make_unique<tf2_ros::TransformListener>(tf_buffer);
  }
};

SlamNode::SlamNode(ros::NodeHandle node, ros::NodeHandle private_node, NodeOptions options,
                   std::function<void()> on_failure)
    : options_(std::move(options)), on_failure_(std::move(on_failure)), node_(node), private_node_(private_node) {
  options_.check();
  pose_ = private_node_.advertise<geometry_msgs::PoseStamped>("pose", 10);
  mask_ = private_node_.advertise<sensor_msgs::Image>("dynamic_mask", 2);
  path_ = private_node_.advertise<nav_msgs::Path>("path", 1, /*latch=*/true);
  map_points_ = private_node_.advertise<sensor_msgs::PointCloud2>("map_points", 1, true);
  dense_cloud_ = private_node_.advertise<sensor_msgs::PointCloud2>("dense_cloud", 1, true);
  grid_ = private_node_.advertise<nav_msgs::OccupancyGrid>("occupancy_grid", 1, true);
  save_map_ = private_node_.advertiseService("save_map", &SlamNode::onSaveMap, this);
  // Made now when the settings have the calibration, so that the first frame does not wait for the models.
  makeSlam(/*warn=*/false);
  subscriptions_ = std::make_unique<Subscriptions>(options_);
  const auto queue = static_cast<std::uint32_t>(options_.sync_queue);
  subscriptions_->rgb = node_.subscribe<sensor_msgs::Image>(
      options_.rgb_topic, queue,
      [this](const sensor_msgs::ImageConstPtr& m) { onPair(subscriptions_->pairer.addColour(m)); });
  subscriptions_->depth = node_.subscribe<sensor_msgs::Image>(
      options_.depth_topic, queue,
      [this](const sensor_msgs::ImageConstPtr& m) { onPair(subscriptions_->pairer.addDepth(m)); });
  subscriptions_->camera_info = node_.subscribe(options_.camera_info_topic, 1, &SlamNode::onCameraInfo, this);
  if (options_.cloud_rate > 0)
    cloud_timer_ = node_.createWallTimer(ros::WallDuration(1.0 / options_.cloud_rate), &SlamNode::onCloudTimer, this);
  if (options_.dense && options_.dense_rate > 0)
    dense_timer_ = node_.createWallTimer(ros::WallDuration(1.0 / options_.dense_rate), &SlamNode::onDenseTimer, this);
  tracker_ = std::thread([this] { trackLoop(); });
}

SlamNode::~SlamNode() { stop(); }

void SlamNode::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& info) {
  std::lock_guard lock(camera_mutex_);
  camera_info_ = rosbag::cameraIntrinsics(*info);
}

void SlamNode::onPair(const std::optional<StampPairer::Pair>& pair) {
  if (!pair) return;
  const auto& [rgb, depth] = *pair;
  StampedFrame frame;
  try {
    frame.bgr = rosbag::colourImage(*rgb, fmt::format("topic '{}'", options_.rgb_topic));
    frame.depth = rosbag::depthImage(*depth, fmt::format("topic '{}'", options_.depth_topic));
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(5, "amos_slam_node: frame at %f left out: %s", rgb->header.stamp.toSec(), e.what());
    return;
  }
  frame.stamp = rgb->header.stamp;
  frame.timestamp = rosbag::stampSeconds(rgb->header.stamp);
  frame.arrival = std::chrono::steady_clock::now();
  slot_.put(std::move(frame));
}

bool SlamNode::makeSlam(bool warn) {
  std::optional<core::CameraIntrinsics> info;
  {
    std::lock_guard lock(camera_mutex_);
    info = camera_info_;
  }
  if (!info && !rosbag::settingsHaveCalibration(options_.settings_file)) {
    if (warn)
      ROS_WARN_THROTTLE(5, "amos_slam_node: waiting for camera_info on '%s' (the settings have no calibration)",
                        options_.camera_info_topic.c_str());
    return false;
  }
  Options o;
  o.settings_yaml = rosbag::settingsTextWithCamera(options_.settings_file, info,
                                                   fmt::format("topic '{}'", options_.camera_info_topic));
  o.mode = parseMode(options_.mode);
  o.models_dir = options_.models_dir;
  o.deterministic = options_.deterministic;
  o.dense = options_.dense;
  slam_ = std::make_unique<Slam>(o);
#ifdef AMOS_NODE_REPORT
  report_ = std::make_unique<NodeReport>(options_.settings_file, options_.mode, sourceName());
#endif
  slam_ready_.store(true, std::memory_order_release);
  ROS_INFO("amos_slam_node: tracking (%s, mode %s)", options_.settings_file.c_str(), options_.mode.c_str());
  return true;
}

void SlamNode::trackLoop() {
  while (std::optional<StampedFrame> frame = slot_.take()) {
    try {
      if (!slam_ && !makeSlam(/*warn=*/true)) continue;
      const FrameResult result = slam_->track(frame->bgr, frame->depth, frame->timestamp);
      publish(result, *frame);
#ifdef AMOS_NODE_REPORT
      report_->add(result, frame->bgr);
#endif
    } catch (const std::exception& e) {
      ROS_ERROR("amos_slam_node: %s; stopping", e.what());
      slot_.close();
      if (on_failure_) on_failure_();
      return;
    }
  }
}

void SlamNode::publish(const FrameResult& result, const StampedFrame& frame) {
  if (result.T_wc) {
    pose_.publish(poseStamped(*result.T_wc, frame.stamp, options_.map_frame));
    Eigen::Matrix4d T_parent_child = *result.T_wc;
    std::string child = options_.camera_frame;
    if (!options_.odom_frame.empty()) {
      try {  // map -> odom = T_map_camera * T_odom_camera^-1
        const auto odom_camera = subscriptions_->tf_buffer.lookupTransform(options_.odom_frame, options_.camera_frame,
                                                                           frame.stamp, ros::Duration(0.05));
        geometry_msgs::Pose p;
        p.position.x = odom_camera.transform.translation.x;
        p.position.y = odom_camera.transform.translation.y;
        p.position.z = odom_camera.transform.translation.z;
        p.orientation = odom_camera.transform.rotation;
        T_parent_child = *result.T_wc * poseMatrix(p).inverse();
        child = options_.odom_frame;
      } catch (const tf2::TransformException& e) {
        ROS_WARN_THROTTLE(5, "amos_slam_node: no %s -> %s transform: %s", options_.odom_frame.c_str(),
                          options_.camera_frame.c_str(), e.what());
        child.clear();
      }
    }
    if (!child.empty())
      subscriptions_->broadcaster.sendTransform(
          transformStamped(T_parent_child, frame.stamp, options_.map_frame, child));
  }
  if (mask_.getNumSubscribers() > 0 && !result.dynamic_mask.empty())
    mask_.publish(rosbag::imageMessage(result.dynamic_mask, "mono8", frame.stamp, options_.camera_frame));
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame.arrival).count();
  std::lock_guard lock(stats_mutex_);
  ++stats_.processed;
  if (result.T_wc) ++stats_.published;
  stats_.latency_ms.push_back(ms);
}

void SlamNode::onCloudTimer(const ros::WallTimerEvent&) {
  if (!slam_ready_.load(std::memory_order_acquire) || slam_->finished()) return;
  const ros::Time now = ros::Time::now();
  path_.publish(pathMessage(slam_->trajectory(), options_.map_frame));
  map_points_.publish(cloudMessage(slam_->mapPoints(), {}, now, options_.map_frame));
}

void SlamNode::onDenseTimer(const ros::WallTimerEvent&) {
  if (!slam_ready_.load(std::memory_order_acquire) || slam_->finished()) return;
  const ros::Time now = ros::Time::now();
  if (const std::optional<DenseSnapshot> snapshot = slam_->denseSnapshot())
    dense_cloud_.publish(cloudMessage(snapshot->cloud.points, snapshot->cloud.colours, now, options_.map_frame));
  if (const std::optional<OccupancyGrid> grid = slam_->denseLiveGrid())
    grid_.publish(gridMessage(*grid, now, options_.map_frame));
}

std::string SlamNode::sourceName() const {
  return fmt::format("topics {} + {}", node_.resolveName(options_.rgb_topic), node_.resolveName(options_.depth_topic));
}

std::string SlamNode::writeOutputs(bool final) {
  if (options_.output_dir.empty() || !slam_ready_.load(std::memory_order_acquire)) return "nothing (no ~output_dir)";
  const fs::path dir(options_.output_dir);
  const NodeStats node_stats = stats();
  // What `amos-slam run` writes, by the library's code (amos::Slam::writeOutputs), with the node's frames.
  RunDescription run;
  run.sequence = sourceName();
  run.config = options_.settings_file;
  run.source_kind = "ros";
  run.delivered = node_stats.received;
  run.dropped = node_stats.dropped;
  run.latency_ms = node_stats.latency_ms;
  run.other_outputs = {"node_stats.json", "map.amosmap"};
  if (options_.dense) run.other_outputs.insert(run.other_outputs.end(), kDenseFiles.begin(), kDenseFiles.end());
#ifdef AMOS_NODE_REPORT
  run.other_outputs.push_back("report.html");
#endif
  slam_->writeOutputs(options_.output_dir, run);
  writeNodeStats((dir / "node_stats.json").string(), node_stats, slam_->summary());
  std::vector<std::string> written = Slam::outputNames();
  written.push_back("node_stats.json");
#ifdef AMOS_NODE_REPORT
  report_->write(dir, slam_->trajectory());  // after stats.json, which the page shows
  written.push_back("report.html");
#endif
  if (final) {  // the map and the dense files need the settled map (Slam::finish)
    slam_->saveMap((dir / "map.amosmap").string());
    written.push_back("map.amosmap");
    if (options_.dense) {
      const DenseMap map = slam_->denseMap();
      writeMeshPly(map, (dir / "mesh.ply").string());
      writeCloudPly(map, (dir / "cloud.ply").string());
      DenseMap removed;  // the dynamic readings left out, as run --dense's removed_points.ply
      removed.cloud = map.removed;
      writeCloudPly(removed, (dir / "removed_points.ply").string());
      written.insert(written.end(), {"mesh.ply", "cloud.ply", "removed_points.ply"});
      if (map.grid) {
        writeFloorPlan(map, (dir / "occupancy").string());
        grid_.publish(gridMessage(*map.grid, ros::Time::now(), options_.map_frame));
        written.insert(written.end(), {"occupancy.pgm", "occupancy.yaml"});
      }
    }
  }
  return fmt::format("{} in {}", fmt::join(written, ", "), options_.output_dir);
}

bool SlamNode::onSaveMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  try {
    response.message = writeOutputs(/*final=*/false);
    response.success = true;
  } catch (const std::exception& e) {
    response.message = e.what();
    response.success = false;
  }
  return true;
}

void SlamNode::stop() {
  std::call_once(stopped_, [this] {
    cloud_timer_.stop();
    dense_timer_.stop();
    slot_.close();
    if (tracker_.joinable()) tracker_.join();
    subscriptions_->rgb.shutdown();  // waits for a callback under way
    subscriptions_->depth.shutdown();
    subscriptions_->camera_info.shutdown();
    if (!slam_) return;
    slam_->finish();
    try {
      ROS_INFO("amos_slam_node: wrote %s", writeOutputs(/*final=*/true).c_str());
    } catch (const std::exception& e) {
      ROS_ERROR("amos_slam_node: writing the outputs: %s", e.what());
    }
  });
}

NodeStats SlamNode::stats() const {
  NodeStats s;
  {
    std::lock_guard lock(stats_mutex_);
    s = stats_;
  }
  s.received = slot_.received();
  s.dropped = slot_.dropped();
  return s;
}

}  // namespace amos::node
