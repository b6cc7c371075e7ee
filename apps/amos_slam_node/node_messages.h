#pragma once
// The node's messages from the library's values (include/amos/slam.h, dense_map.h): poses, transforms, paths,
// point clouds and the occupancy grid, and the grid back from its message (for the tests and any consumer).
#include <Eigen/Core>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <sensor_msgs/PointCloud2.h>

#include <string>
#include <vector>

#include "amos/dense_map.h"
#include "amos/slam.h"

namespace amos::node {

geometry_msgs::Pose poseMessage(const Eigen::Matrix4d& T);
Eigen::Matrix4d poseMatrix(const geometry_msgs::Pose& pose);
geometry_msgs::PoseStamped poseStamped(const Eigen::Matrix4d& T_wc, const ros::Time& stamp, const std::string& frame);
// The transform `parent` -> `child` whose matrix is T (a point in child's frame to parent's).
geometry_msgs::TransformStamped transformStamped(const Eigen::Matrix4d& T, const ros::Time& stamp,
                                                 const std::string& parent, const std::string& child);
nav_msgs::Path pathMessage(const std::vector<StampedPose>& trajectory, const std::string& frame);

// x, y, z as float32 and, with colours (one per point), rgb packed in a float32 as PCL and RViz read it.
sensor_msgs::PointCloud2 cloudMessage(const std::vector<Eigen::Vector3d>& points, const std::vector<Rgb>& colours,
                                      const ros::Time& stamp, const std::string& frame);

// The floor plan in the frame of the trajectory (`frame`): cells 0 free, 100 occupied, -1 unknown, row 0 at the
// origin (map_server's PGM is the other way up), origin = the lower-left corner's pose in the world.
nav_msgs::OccupancyGrid gridMessage(const OccupancyGrid& grid, const ros::Time& stamp, const std::string& frame);
// The grid of a message: cells, size and resolution as given, origin (0, 0) in a map frame whose pose in the world
// is the message's origin (T_mw its inverse). Throws std::runtime_error for a message whose data does not fit it.
OccupancyGrid gridFromMessage(const nav_msgs::OccupancyGrid& message);

}  // namespace amos::node
