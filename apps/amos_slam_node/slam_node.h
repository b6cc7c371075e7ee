#pragma once
// amos_slam_node's work (docs/ros.md), a client of the public library API (amos::Slam): colour and depth images
// paired by time stamp as they arrive (StampPairer, bounded by ~sync_queue and ~max_pair_dt), handed to a
// tracking thread through a one-frame slot (LatestFrame: a frame the tracking has no time for is dropped and
// counted); each tracked frame's pose published as geometry_msgs/PoseStamped (~pose) and as the transform map ->
// camera (or map -> odom), its dynamic mask as sensor_msgs/Image (~dynamic_mask); at ~cloud_rate the corrected
// path (~path) and the sparse map (~map_points); with ~dense at ~dense_rate the live dense static cloud
// (~dense_cloud) and the floor plan built from it (~occupancy_grid); at the end (stop()) the final floor plan and
// the outputs in ~output_dir. The service ~save_map writes
// the outputs at any time. The amos::Slam is made at once when the settings have the calibration, else on the first
// frame after a camera_info.
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "amos/core/camera.h"
#include "amos/slam.h"
#include "latest_frame.h"
#include "node_options.h"
#ifdef AMOS_NODE_REPORT
#include "node_report.h"
#endif
#include "stamp_pairer.h"

namespace amos::node {

struct NodeStats {
  std::size_t received = 0;   // colour + depth pairs that reached the slot
  std::size_t dropped = 0;    // of those, replaced by a newer pair before tracking took them
  std::size_t processed = 0;  // tracked (whatever the state)
  std::size_t published = 0;  // of those, with a pose published
  std::vector<double> latency_ms;  // per processed frame: pair complete here -> pose published
};

class SlamNode {
 public:
  // Subscribes and advertises on `node` (topics) and `private_node` (parameters' names: ~pose, ~save_map...).
  // `on_failure` is called (from the tracking thread) when tracking ends with an error (logged), e.g. to end the
  // program.
  SlamNode(ros::NodeHandle node, ros::NodeHandle private_node, NodeOptions options,
           std::function<void()> on_failure = {});
  ~SlamNode();
  SlamNode(const SlamNode&) = delete;
  SlamNode& operator=(const SlamNode&) = delete;

  // Stops taking frames, tracks the one waiting, finishes the Slam, publishes the floor plan (with
  // ~dense) and writes the outputs (with ~output_dir). Idempotent; the destructor calls it.
  void stop();
  NodeStats stats() const;

 private:
  struct Subscriptions;
  void onPair(const std::optional<StampPairer::Pair>& pair);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& info);
  bool onSaveMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response);
  void onCloudTimer(const ros::WallTimerEvent&);
  void onDenseTimer(const ros::WallTimerEvent&);
  void trackLoop();
  bool makeSlam(bool warn);  // false while the calibration waits for camera_info (`warn`: say so, throttled)
  void publish(const FrameResult& result, const StampedFrame& frame);
  std::string writeOutputs(bool final);
  std::string sourceName() const;  // "topics /rgb + /depth", resolved

  NodeOptions options_;
  std::function<void()> on_failure_;
  ros::NodeHandle node_, private_node_;
  std::unique_ptr<Subscriptions> subscriptions_;
  ros::Publisher pose_, mask_, path_, map_points_, dense_cloud_, grid_;
  ros::ServiceServer save_map_;
  ros::WallTimer cloud_timer_, dense_timer_;
  std::mutex camera_mutex_;
  std::optional<core::CameraIntrinsics> camera_info_;  // guarded by camera_mutex_
  LatestFrame slot_;
  std::unique_ptr<Slam> slam_;  // made and used by the tracking thread; read by the timer and the service
#ifdef AMOS_NODE_REPORT
  std::unique_ptr<NodeReport> report_;  // made with slam_
#endif
  std::atomic<bool> slam_ready_{false};
  mutable std::mutex stats_mutex_;
  NodeStats stats_;  // guarded by stats_mutex_ (but received / dropped: the slot's)
  std::once_flag stopped_;
  std::thread tracker_;
};

}  // namespace amos::node
