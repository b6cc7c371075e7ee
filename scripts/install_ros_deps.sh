#!/usr/bin/env bash
# Installs the Debian packages of the optional ROS 1 part (AMOS_WITH_ROS: the bag sequence source amos_rosbag and the
# node amos_slam_node, docs/ros.md) on top of scripts/install_deps.sh's. Debian 12 carries ROS 1 (Noetic-era
# packages); ROS 2 is not in Debian 12. Idempotent.
set -euo pipefail
source "$(dirname "$0")/apt_install.sh"
apt_install install_ros_deps \
  ros-core-dev libroscpp-dev librosbag-dev libcv-bridge-dev libimage-transport-dev libtf2-ros-dev \
  libsensor-msgs-dev libnav-msgs-dev libgeometry-msgs-dev libtf2-msgs-dev libstd-srvs-dev libmessage-filters-dev \
  python3-rosbag python3-roslaunch python3-rosmaster
