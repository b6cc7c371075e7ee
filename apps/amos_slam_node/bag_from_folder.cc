// amos_bag_from_folder: writes a TUM/Bonn-layout sequence folder as a ROS 1 bag (rosbag/bag_writer.h), e.g. to run
// `amos-slam run --sequence X.bag` or to play it into amos_slam_node (docs/ros.md).
#include <CLI/CLI.hpp>

#include <cstdio>

#include "amos/config/settings.h"
#include "amos/io/dataset.h"
#include "amos/rosbag/bag_writer.h"

int main(int argc, char** argv) {
  CLI::App app("Write a TUM/Bonn-layout sequence folder as a ROS 1 bag (colour, depth and camera_info topics)");
  std::string folder, bag, config;
  amos::rosbag::BagWriteOptions options;
  app.add_option("folder", folder, "Sequence folder (rgb/, depth/, rgb.txt, depth.txt)")->required();
  app.add_option("bag", bag, "The bag to write")->required();
  app.add_option("--config", config, "Settings file: its calibration goes into camera_info messages and its "
                                     "DepthMapFactor scales 32FC1 depth (default: no camera_info, factor 5000)");
  app.add_option("--compression", options.compression, "none | bz2 | lz4")->capture_default_str();
  app.add_option("--colour-encoding", options.colour_encoding, "rgb8 | bgr8")->capture_default_str();
  app.add_option("--depth-encoding", options.depth_encoding, "16UC1 (raw) | 32FC1 (metres)")->capture_default_str();
  app.add_option("--rgb-topic", options.topics.rgb)->capture_default_str();
  app.add_option("--depth-topic", options.topics.depth)->capture_default_str();
  app.add_option("--camera-info-topic", options.topics.camera_info)->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    if (!config.empty()) {
      const amos::config::Settings settings = amos::config::loadSettings(config);
      options.camera = settings.camera;
      options.depth_factor = settings.depth_factor;
    }
    const amos::io::SequenceIndex index = amos::io::indexSequence(folder);
    amos::rosbag::writeBag(index, bag, options);
    std::printf("%zu frames written to %s\n", index.frames.size(), bag.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "amos_bag_from_folder: %s\n", e.what());
    return 1;
  }
  return 0;
}
