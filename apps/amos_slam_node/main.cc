// amos_slam_node: Amos-SLAM as a ROS 1 node (docs/ros.md). Parameters in the node's private namespace
// (node_options.h); SIGINT / SIGTERM (or a tracking error) end it after the outputs are written and the floor plan
// published, while ROS is still up.
#include <ros/ros.h>
#include <semaphore.h>

#include <csignal>
#include <cstdio>

#include "amos/core/error.h"
#include "node_options.h"
#include "slam_node.h"

namespace {

sem_t g_end;  // posted by the signal handler (sem_post is async-signal-safe) or a tracking error

void onSignal(int) { sem_post(&g_end); }

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "amos_slam_node", ros::init_options::NoSigintHandler);
  sem_init(&g_end, 0, 0);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  try {
    ros::NodeHandle node, private_node("~");
    amos::node::SlamNode slam_node(node, private_node, amos::node::readNodeOptions(private_node),
                                   [] { sem_post(&g_end); });
    ros::AsyncSpinner spinner(2);
    spinner.start();
    while (sem_wait(&g_end) != 0) {
    }
    slam_node.stop();
    spinner.stop();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "amos_slam_node: %s\n", e.what());
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return 0;
}
