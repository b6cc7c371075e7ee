#pragma once
// Which topics of a ROS 1 bag hold the colour images, the depth images and the camera calibration. Without a choice
// (--rgb-topic / --depth-topic) the first known driver's names that the bag has are taken: the TUM RGB-D bags',
// openni2_launch's (depth registered to colour, then raw) and realsense2_camera's (depth aligned to colour, then
// raw).
#include <string>
#include <vector>

namespace amos::rosbag {

struct BagTopics {
  std::string rgb;          // sensor_msgs/Image: rgb8, bgr8, rgba8, bgra8 or mono8
  std::string depth;        // sensor_msgs/Image: 16UC1 / mono16 (raw, DepthMapFactor) or 32FC1 (metres)
  std::string camera_info;  // sensor_msgs/CameraInfo of the colour camera ("" = none is read)
};

struct KnownTopics {
  std::string driver;  // "tum", "openni2", "openni2-raw", "realsense", "realsense-raw"
  BagTopics topics;
};
const std::vector<KnownTopics>& knownTopics();

// The topics to read from a bag (named `bag` in errors) that has `in_bag`: the `requested` ones where given, the
// rest from the first known driver whose colour and depth topics are both there (its camera_info topic only when
// the bag has it). Throws core::Error naming the bag and the topic that is not there (and the bag's image topics).
BagTopics chooseTopics(const std::vector<std::string>& in_bag, const BagTopics& requested, const std::string& bag);

}  // namespace amos::rosbag
