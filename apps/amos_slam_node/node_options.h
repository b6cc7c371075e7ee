#pragma once
// amos_slam_node's parameters (docs/ros.md): the settings, the front end, the frames, the topics, the queues and
// the outputs. Read from the node's private parameters (~settings_file, ~mode, ...), each with a default but the
// settings file.
#include <ros/node_handle.h>

#include <string>

namespace amos::node {

struct NodeOptions {
  std::string settings_file;      // ~settings_file (required): configs/*.yaml; the calibration may come from
                                  //   camera_info (rosbag/bag_settings.h says which wins)
  std::string mode = "full";      // ~mode: none | prior | geometry | full
  std::string models_dir;         // ~models_dir ("" = looked for as amos::Options does)
  bool deterministic = false;     // ~deterministic: local mapping in lock-step (as run --deterministic)
  bool dense = false;             // ~dense: the dense static cloud and the floor plan (a build with Open3D)
  std::string map_frame = "map";  // ~map_frame
  std::string camera_frame = "camera";  // ~camera_frame: the camera's frame as this node publishes it
  // ~odom_frame: when set, the transform published is map -> odom (the correction that, with the odometry's
  // odom -> camera_frame, gives the SLAM pose), read from tf; else map -> camera_frame.
  std::string odom_frame;
  std::string rgb_topic = "camera/rgb/image_color";      // ~rgb_topic
  std::string depth_topic = "camera/depth/image";        // ~depth_topic
  std::string camera_info_topic = "camera/rgb/camera_info";  // ~camera_info_topic
  int sync_queue = 10;            // ~sync_queue: colour / depth messages waiting to be paired by time stamp
  double max_pair_dt = 0.02;      // ~max_pair_dt (s): colour and depth further apart than this are not a pair
  double cloud_rate = 1.0;        // ~cloud_rate (Hz): how often the path and the sparse map are published
  // ~dense_rate (Hz): with ~dense, how often the live dense cloud and the occupancy grid built from it are published
  // while the node runs (0 = only the final ones at shutdown).
  double dense_rate = 0.5;
  std::string output_dir;         // ~output_dir: written at shutdown and by ~save_map ("" = nothing written)
  void check() const;             // throws core::Error naming the parameter
};

NodeOptions readNodeOptions(const ros::NodeHandle& private_node);

}  // namespace amos::node
