#pragma once
// A ROS 1 bag as a recorded RGB-D sequence (no ROS master involved): its colour and depth image messages paired
// one-to-one by header time stamp as the folder reader pairs rgb.txt and depth.txt (io::associateStamps, window
// max_dt), its camera calibration (the first sensor_msgs/CameraInfo) and ground truth (groundtruth.txt beside the
// bag). Compressed bags (bz2, lz4) are read as they are. Every image message is checked while indexing, so a bag
// that is damaged, lacks a topic or holds images of another encoding is an error naming the bag and the topic before
// any frame is tracked.
#include <opencv2/core.hpp>
#include <ros/time.h>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "amos/core/camera.h"
#include "amos/io/dataset.h"
#include "amos/rosbag/bag_topics.h"

namespace amos::rosbag {

struct BagOptions {
  BagTopics topics;      // "" = chosen from the known drivers' names (chooseTopics)
  double max_dt = 0.02;  // the pairing window (s), as io::indexSequence's
};

struct BagIndex {
  std::string bag;
  BagTopics topics;  // as chosen
  // The paired frames: t_rgb / t_depth are the messages' header stamps, rgb_file / depth_file name them
  // ("<bag>:<topic>/<stamp>.png": an output named by the frame takes the stamp); groundtruth_file as a folder's.
  io::SequenceIndex sequence;
  // Per frame: the position of its colour and of its depth message among its topic's messages (bag order).
  std::vector<std::pair<std::size_t, std::size_t>> messages;
  std::optional<core::CameraIntrinsics> camera_info;  // from the first CameraInfo message, when there is one
  cv::Size image_size;                                // of the first colour message
};

// Throws core::Error naming the bag (and topic) when it cannot be read, lacks a topic, holds a message of another
// type or an image of an encoding not read (image_messages.h), or has no pair of colour and depth stamps within
// max_dt.
BagIndex indexBag(const std::string& bag, const BagOptions& options = {});

// Keeps `count` frames (0 = all) from `first` on (--first-frame, --max-frames); throws core::Error naming the bag
// when it has no frame `first`.
void selectFrames(BagIndex& index, std::size_t first, std::size_t count);

// The topics indexBag would read (chooseTopics over the bag's topics), without reading any image.
BagTopics bagTopics(const std::string& bag, const BagTopics& requested = {});
// The first CameraInfo message on `topic` as intrinsics (plumb_bob / rational_polynomial: k1 k2 p1 p2 k3), or
// nothing when the topic is empty or has no message.
std::optional<core::CameraIntrinsics> readCameraInfo(const std::string& bag, const std::string& topic);

// A header stamp in seconds (ros::Time::toSec). A folder's time stamp written with ros::Time::fromSec reads back as
// the same double: bag_reader_test.cc and bag_run_test.cc check it bit for bit.
double stampSeconds(const ros::Time& stamp);

}  // namespace amos::rosbag
