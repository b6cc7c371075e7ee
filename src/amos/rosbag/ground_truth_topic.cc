#include "amos/rosbag/ground_truth_topic.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <set>

#include "amos/core/error.h"
#include "amos/rosbag/bag_file.h"
#include "amos/rosbag/bag_index.h"

namespace amos::rosbag {

namespace {

core::SE3 poseOf(const geometry_msgs::Point& t, const geometry_msgs::Quaternion& q) {
  core::SE3 T = core::SE3::Identity();
  T.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(t.x, t.y, t.z);
  return T;
}

geometry_msgs::Point pointOf(const geometry_msgs::Vector3& v) {
  geometry_msgs::Point p;
  p.x = v.x;
  p.y = v.y;
  p.z = v.z;
  return p;
}

io::StampedPose stamped(const ros::Time& stamp, const core::SE3& T_wc) { return {stampSeconds(stamp), T_wc}; }

std::string withoutSlash(const std::string& frame) {
  return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame;
}

const char* const kAccepted =
    "geometry_msgs/PoseStamped, geometry_msgs/TransformStamped, nav_msgs/Odometry or tf2_msgs/TFMessage";

// The poses of one message (none for a /tf message without the frame pair; its pairs go to `seen`).
void addPoses(const ::rosbag::MessageInstance& m, const std::string& bag, const GroundTruthTopic& source,
              std::vector<io::StampedPose>& poses, std::set<std::string>& seen) {
  const std::string& type = m.getDataType();
  if (type == "geometry_msgs/PoseStamped") {
    const auto p = instantiateOrThrow<geometry_msgs::PoseStamped>(m, bag);
    poses.push_back(stamped(p->header.stamp, poseOf(p->pose.position, p->pose.orientation)));
  } else if (type == "geometry_msgs/TransformStamped") {
    const auto t = instantiateOrThrow<geometry_msgs::TransformStamped>(m, bag);
    poses.push_back(stamped(t->header.stamp, poseOf(pointOf(t->transform.translation), t->transform.rotation)));
  } else if (type == "nav_msgs/Odometry") {
    const auto o = instantiateOrThrow<nav_msgs::Odometry>(m, bag);
    poses.push_back(stamped(o->header.stamp, poseOf(o->pose.pose.position, o->pose.pose.orientation)));
  } else if (type == "tf2_msgs/TFMessage") {
    const auto tf = instantiateOrThrow<tf2_msgs::TFMessage>(m, bag);
    for (const geometry_msgs::TransformStamped& t : tf->transforms) {
      const std::string parent = withoutSlash(t.header.frame_id), child = withoutSlash(t.child_frame_id);
      if (parent == withoutSlash(source.parent_frame) && child == withoutSlash(source.child_frame)) {
        poses.push_back(stamped(t.header.stamp, poseOf(pointOf(t.transform.translation), t.transform.rotation)));
      } else {
        seen.insert(fmt::format("{} -> {}", parent, child));
      }
    }
  } else {
    throw core::Error(fmt::format("bag '{}': ground-truth topic '{}' holds {} messages; expected {}", bag,
                                  source.topic, type, kAccepted));
  }
}

}  // namespace

void GroundTruthTopic::check() const {
  core::require(!parent_frame.empty() && !child_frame.empty(),
                "--groundtruth-parent-frame / --groundtruth-child-frame must not be empty");
}

std::vector<io::StampedPose> readGroundTruthTopic(const std::string& bag, const GroundTruthTopic& source) {
  source.check();
  ::rosbag::Bag reader;
  openBag(reader, bag);
  const std::vector<std::string> topics = topicsOf(reader);
  core::require(std::find(topics.begin(), topics.end(), source.topic) != topics.end(),
                fmt::format("bag '{}' has no ground-truth topic '{}'; its topics: {}", bag, source.topic,
                            fmt::join(topics, ", ")));
  std::vector<io::StampedPose> poses;
  std::set<std::string> seen;
  forEachMessage(reader, bag, source.topic, [&](const ::rosbag::MessageInstance& m, std::size_t) {
    addPoses(m, bag, source, poses, seen);
    return true;
  });
  core::require(!poses.empty(),
                fmt::format("bag '{}': ground-truth topic '{}' has no pose{}", bag, source.topic,
                            seen.empty() ? std::string()
                                         : fmt::format(" from '{}' to '{}' (its transforms: {})", source.parent_frame,
                                                       source.child_frame, fmt::join(seen, ", "))));
  // A /tf recording interleaves publishers: the poses by time, as a groundtruth.txt lists them.
  std::stable_sort(poses.begin(), poses.end(),
                   [](const io::StampedPose& a, const io::StampedPose& b) { return a.timestamp < b.timestamp; });
  return poses;
}

std::vector<io::StampedPose> takeGroundTruthTopic(const std::string& bag, const GroundTruthTopic& source,
                                                  io::SequenceIndex& sequence) {
  std::vector<io::StampedPose> poses = readGroundTruthTopic(bag, source);
  sequence.groundtruth_file.clear();
  return poses;
}

}  // namespace amos::rosbag
