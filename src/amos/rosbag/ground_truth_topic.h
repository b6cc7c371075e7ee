#pragma once
// Ground truth recorded in a bag on a topic of its own (run --groundtruth-topic; docs/ros.md): the poses of the
// camera in the world, from geometry_msgs/PoseStamped, geometry_msgs/TransformStamped, nav_msgs/Odometry or
// tf2_msgs/TFMessage (/tf: only the transforms from `parent_frame` to `child_frame`, as the TUM RGB-D bags carry
// their ground truth as /world -> /kinect; frame names compared without a leading '/'; a transform given through
// other frames is not chained). Each pose is stamped with its header's stamp (bag_index.h's stampSeconds).
#include <string>
#include <vector>

#include "amos/io/dataset.h"
#include "amos/io/trajectory.h"

namespace amos::rosbag {

struct GroundTruthTopic {
  std::string topic;                      // "" = none
  std::string parent_frame = "/world";    // for tf2_msgs/TFMessage: the world's frame
  std::string child_frame = "/kinect";    // for tf2_msgs/TFMessage: the camera's frame
  void check() const;                     // throws core::Error naming the option
};

// The topic's poses in bag order. Throws core::Error naming the bag and the topic when the bag has no such topic,
// the topic holds another message type, or it has no pose (for /tf: none from parent_frame to child_frame, with
// the frame pairs it has).
std::vector<io::StampedPose> readGroundTruthTopic(const std::string& bag, const GroundTruthTopic& source);

// readGroundTruthTopic for the indexed bag `sequence` (run --sequence X.bag and amos::SequenceFolder): the topic
// asked for wins over a groundtruth.txt beside the bag, so the index forgets that file.
std::vector<io::StampedPose> takeGroundTruthTopic(const std::string& bag, const GroundTruthTopic& source,
                                                  io::SequenceIndex& sequence);

}  // namespace amos::rosbag
