#!/usr/bin/env bash
# The node's latency and dropped share on a sequence played at its recorded rate (docs/ros.md): the folder is
# written as a bag (amos_bag_from_folder), a ROS master of its own is started on a free loopback port, the node runs
# with the given settings and mode, `rosbag play` plays the bag once, then the node is stopped (SIGINT) and its
# node_stats.json printed. Usage: scripts/ros_node_latency.sh [FOLDER] [CONFIG] [MODE] [OUT]
set -euo pipefail
cd "$(dirname "$0")/.."
folder=${1:-../shared/data/bonn_crowd_dev}
config=${2:-configs/bonn.yaml}
mode=${3:-full}
out=${4:-out/ros_node_latency}
mkdir -p "$out"
out=$(cd "$out" && pwd)
bin=build/bin
if [ ! -x "$bin/amos_slam_node" ]; then
  echo "build/bin/amos_slam_node is missing: build with -DAMOS_WITH_ROS=ON" >&2
  exit 1
fi
"$bin/amos_bag_from_folder" "$folder" "$out/sequence.bag" --config "$config"
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://127.0.0.1:$port ROS_IP=127.0.0.1 ROS_HOME=$out/ros_home
rosmaster --core -p "$port" > "$out/rosmaster.log" 2>&1 &
master=$!
node=""
cleanup() {
  [ -n "$node" ] && kill -INT "$node" 2>/dev/null && wait "$node" || true
  kill "$master" 2>/dev/null && wait "$master" || true
}
trap cleanup EXIT
for _ in $(seq 100); do rostopic list > /dev/null 2>&1 && break; sleep 0.1; done
"$bin/amos_slam_node" _settings_file:="$PWD/$config" _mode:="$mode" _output_dir:="$out/node" \
  _rgb_topic:=/camera/rgb/image_color _depth_topic:=/camera/depth/image _camera_info_topic:=/camera/rgb/camera_info \
  > "$out/node.log" 2>&1 &
node=$!
# The node subscribes once its settings and models are read; the first frames played before that would be lost.
for _ in $(seq 300); do rostopic info /camera/depth/image 2>/dev/null | grep -q amos_slam_node && break; sleep 0.1; done
rosbag play --quiet "$out/sequence.bag" > "$out/play.log" 2>&1
kill -INT "$node"
wait "$node"
node=""
cat "$out/node/node_stats.json"
