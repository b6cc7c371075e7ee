#pragma once
// sensor_msgs/Image <-> cv::Mat for the bag source and the node, without cv_bridge: the few encodings an RGB-D
// camera gives. Errors name `where` (the bag or node, the topic and the message) and the encoding. And
// sensor_msgs/CameraInfo <-> core::CameraIntrinsics.
#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <string>

#include "amos/core/camera.h"

namespace amos::rosbag {

// A colour image as the SLAM loop takes it: CV_8UC3 BGR (a new buffer). rgb8, bgr8, rgba8, bgra8 and mono8 are
// converted; any other encoding (or a message whose size does not fit its header) throws core::Error.
cv::Mat colourImage(const sensor_msgs::Image& msg, const std::string& where);
// A depth image as the folder's PNGs give it (a new buffer): CV_16U raw units (16UC1, mono16; DepthMapFactor
// applies) or CV_32F metres (32FC1). Any other encoding throws core::Error.
cv::Mat depthImage(const sensor_msgs::Image& msg, const std::string& where);
// Whether colourImage / depthImage take this encoding (what the index checks on every message).
bool isColourEncoding(const std::string& encoding);
bool isDepthEncoding(const std::string& encoding);

// A message holding `image` (CV_8UC3 with encoding bgr8 or rgb8, CV_8UC1 mono8, CV_16UC1 16UC1, CV_32FC1 32FC1, or
// another type with a matching encoding for tests of wrong encodings), with that header.
sensor_msgs::Image imageMessage(const cv::Mat& image, const std::string& encoding, const ros::Time& stamp,
                                const std::string& frame_id);

// A CameraInfo's calibration: K's fx fy cx cy, D's first five (plumb_bob, rational_polynomial: k1 k2 p1 p2 k3), the
// image size.
core::CameraIntrinsics cameraIntrinsics(const sensor_msgs::CameraInfo& info);
// The CameraInfo of a calibration (plumb_bob, no rectification).
sensor_msgs::CameraInfo cameraInfoMessage(const core::CameraIntrinsics& camera, const ros::Time& stamp,
                                          const std::string& frame_id);

}  // namespace amos::rosbag
