#pragma once
// Writes a TUM/Bonn-layout sequence folder as a ROS 1 bag, the way a camera driver's recording looks: per frame a
// colour sensor_msgs/Image, a depth Image and a CameraInfo, stamped with the folder's time stamps (bag time = header
// stamp). For the tests (bags made from synthetic sequences) and `amos_bag_from_folder` (a bag of a TUM sequence).
#include <optional>
#include <string>

#include "amos/core/camera.h"
#include "amos/io/dataset.h"
#include "amos/rosbag/bag_topics.h"

namespace amos::rosbag {

struct BagWriteOptions {
  BagTopics topics = {"/camera/rgb/image_color", "/camera/depth/image", "/camera/rgb/camera_info"};  // TUM's
  std::string compression = "none";    // none | bz2 | lz4
  std::string colour_encoding = "rgb8";  // rgb8 | bgr8 (as the TUM bags: rgb8)
  // 16UC1: the PNGs' raw values (DepthMapFactor applies when read); 32FC1: metres (raw / depth_factor), as the TUM
  // bags' /camera/depth/image.
  std::string depth_encoding = "16UC1";
  double depth_factor = 5000.0;
  std::optional<core::CameraIntrinsics> camera;  // camera_info messages when set (topics.camera_info)
  std::string frame_id = "camera_rgb_optical_frame";
  void check() const;  // throws core::Error naming the option
};

// Throws core::Error naming the file that cannot be read or the bag that cannot be written.
void writeBag(const io::SequenceIndex& sequence, const std::string& bag, const BagWriteOptions& options);

}  // namespace amos::rosbag
