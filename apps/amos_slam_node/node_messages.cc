#include "node_messages.h"

#include <fmt/format.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <Eigen/Geometry>
#include <cstring>
#include <stdexcept>

namespace amos::node {

namespace {

std::int8_t rosCell(std::uint8_t cell) {
  if (cell == OccupancyGrid::kFree) return 0;
  if (cell == OccupancyGrid::kOccupied) return 100;
  return -1;
}

std::uint8_t amosCell(std::int8_t cell) {
  if (cell == 0) return OccupancyGrid::kFree;
  if (cell == 100) return OccupancyGrid::kOccupied;
  return OccupancyGrid::kUnknown;
}

}  // namespace

geometry_msgs::Pose poseMessage(const Eigen::Matrix4d& T) {
  geometry_msgs::Pose pose;
  pose.position.x = T(0, 3);
  pose.position.y = T(1, 3);
  pose.position.z = T(2, 3);
  const Eigen::Quaterniond q(Eigen::Matrix3d(T.block<3, 3>(0, 0)));
  pose.orientation.x = q.x();
  pose.orientation.y = q.y();
  pose.orientation.z = q.z();
  pose.orientation.w = q.w();
  return pose;
}

Eigen::Matrix4d poseMatrix(const geometry_msgs::Pose& pose) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  const Eigen::Quaterniond q(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z);
  T.block<3, 3>(0, 0) = q.normalized().toRotationMatrix();
  T.block<3, 1>(0, 3) = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return T;
}

geometry_msgs::PoseStamped poseStamped(const Eigen::Matrix4d& T_wc, const ros::Time& stamp, const std::string& frame) {
  geometry_msgs::PoseStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame;
  msg.pose = poseMessage(T_wc);
  return msg;
}

geometry_msgs::TransformStamped transformStamped(const Eigen::Matrix4d& T, const ros::Time& stamp,
                                                 const std::string& parent, const std::string& child) {
  geometry_msgs::TransformStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = parent;
  msg.child_frame_id = child;
  const geometry_msgs::Pose pose = poseMessage(T);
  msg.transform.translation.x = pose.position.x;
  msg.transform.translation.y = pose.position.y;
  msg.transform.translation.z = pose.position.z;
  msg.transform.rotation = pose.orientation;
  return msg;
}

nav_msgs::Path pathMessage(const std::vector<StampedPose>& trajectory, const std::string& frame) {
  nav_msgs::Path path;
  path.header.frame_id = frame;
  for (const StampedPose& p : trajectory) {
    ros::Time stamp;
    stamp.fromSec(p.timestamp);
    path.poses.push_back(poseStamped(p.T_wc, stamp, frame));
  }
  if (!path.poses.empty()) path.header.stamp = path.poses.back().header.stamp;
  return path;
}

sensor_msgs::PointCloud2 cloudMessage(const std::vector<Eigen::Vector3d>& points, const std::vector<Rgb>& colours,
                                      const ros::Time& stamp, const std::string& frame) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.stamp = stamp;
  cloud.header.frame_id = frame;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  const bool coloured = !colours.empty() && colours.size() == points.size();
  if (coloured) modifier.setPointCloud2FieldsByString(2, "xyz", "rgb");
  else modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(points.size());
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  for (std::size_t i = 0; i < points.size(); ++i, ++x, ++y, ++z) {
    *x = static_cast<float>(points[i].x());
    *y = static_cast<float>(points[i].y());
    *z = static_cast<float>(points[i].z());
  }
  if (coloured) {
    sensor_msgs::PointCloud2Iterator<std::uint8_t> r(cloud, "r"), g(cloud, "g"), b(cloud, "b");
    for (std::size_t i = 0; i < points.size(); ++i, ++r, ++g, ++b) {
      *r = colours[i][0];
      *g = colours[i][1];
      *b = colours[i][2];
    }
  }
  return cloud;
}

nav_msgs::OccupancyGrid gridMessage(const OccupancyGrid& grid, const ros::Time& stamp, const std::string& frame) {
  nav_msgs::OccupancyGrid msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame;
  msg.info.map_load_time = stamp;
  msg.info.resolution = static_cast<float>(grid.resolution);
  msg.info.width = static_cast<std::uint32_t>(grid.cols);
  msg.info.height = static_cast<std::uint32_t>(grid.rows);
  Eigen::Matrix4d corner_in_map = Eigen::Matrix4d::Identity();
  corner_in_map.block<2, 1>(0, 3) = grid.origin;
  msg.info.origin = poseMessage(grid.T_mw.inverse() * corner_in_map);
  msg.data.resize(grid.cells.size());
  for (int row = 0; row < grid.rows; ++row) {  // the message's row 0 is the grid's bottom row
    for (int col = 0; col < grid.cols; ++col)
      msg.data[static_cast<std::size_t>(row) * grid.cols + col] = rosCell(grid.at(grid.rows - 1 - row, col));
  }
  return msg;
}

OccupancyGrid gridFromMessage(const nav_msgs::OccupancyGrid& msg) {
  OccupancyGrid grid;
  grid.rows = static_cast<int>(msg.info.height);
  grid.cols = static_cast<int>(msg.info.width);
  if (msg.data.size() != static_cast<std::size_t>(grid.rows) * grid.cols)
    throw std::runtime_error(fmt::format("occupancy grid message: {} cells for {}x{}", msg.data.size(), grid.cols,
                                         grid.rows));
  grid.resolution = msg.info.resolution;
  grid.T_mw = poseMatrix(msg.info.origin).inverse();
  grid.cells.resize(msg.data.size());
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col)
      grid.cells[static_cast<std::size_t>(grid.rows - 1 - row) * grid.cols + col] =
          amosCell(msg.data[static_cast<std::size_t>(row) * grid.cols + col]);
  }
  return grid;
}

}  // namespace amos::node
