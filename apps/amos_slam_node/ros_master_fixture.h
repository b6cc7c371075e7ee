#pragma once
// A ROS master of the test's own (rosmaster --core on a free loopback port, ROS_HOME in a scratch folder), started
// before the first test of the process and stopped after the last; ros::init'ed against it.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <ros/ros.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "amos/testing/scratch_dir.h"

extern char** environ;

namespace amos::node::test {

// A port the kernel had free a moment ago (bound to port 0 and released).
inline int freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof(address);
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address));
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return ntohs(address.sin_port);
}

class RosMaster : public ::testing::Environment {
 public:
  void SetUp() override {
    const std::string home = testing::scratchDir("amos_ros_home").string();
    const std::string port = std::to_string(freePort());
    ::setenv("ROS_HOME", home.c_str(), 1);
    ::setenv("ROS_MASTER_URI", ("http://127.0.0.1:" + port).c_str(), 1);
    ::setenv("ROS_IP", "127.0.0.1", 1);
    const char* argv[] = {"rosmaster", "--core", "-p", port.c_str(), nullptr};
    ASSERT_EQ(::posix_spawnp(&pid_, "rosmaster", nullptr, nullptr, const_cast<char**>(argv), environ), 0)
        << "rosmaster not found: run scripts/install_ros_deps.sh";
    int argc = 0;
    ros::init(argc, nullptr, "amos_slam_node_test", ros::init_options::NoSigintHandler);
    // The master is another process: wait for it to answer, a bounded number of times.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!ros::master::check()) {
      ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "rosmaster on port " << port << " did not answer";
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ros::start();
  }

  void TearDown() override {
    ros::shutdown();
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
  }

 private:
  pid_t pid_ = -1;
};

}  // namespace amos::node::test
