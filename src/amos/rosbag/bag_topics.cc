#include "amos/rosbag/bag_topics.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "amos/core/error.h"

namespace amos::rosbag {

namespace {

bool has(const std::vector<std::string>& topics, const std::string& topic) {
  return std::find(topics.begin(), topics.end(), topic) != topics.end();
}

std::string listed(const std::vector<std::string>& topics) {
  return topics.empty() ? std::string("none") : fmt::format("{}", fmt::join(topics, ", "));
}

}  // namespace

const std::vector<KnownTopics>& knownTopics() {
  static const std::vector<KnownTopics> known = {
      {"tum", {"/camera/rgb/image_color", "/camera/depth/image", "/camera/rgb/camera_info"}},
      {"openni2", {"/camera/rgb/image_raw", "/camera/depth_registered/image_raw", "/camera/rgb/camera_info"}},
      {"openni2-raw", {"/camera/rgb/image_raw", "/camera/depth/image_raw", "/camera/rgb/camera_info"}},
      {"realsense",
       {"/camera/color/image_raw", "/camera/aligned_depth_to_color/image_raw", "/camera/color/camera_info"}},
      {"realsense-raw", {"/camera/color/image_raw", "/camera/depth/image_rect_raw", "/camera/color/camera_info"}},
  };
  return known;
}

BagTopics chooseTopics(const std::vector<std::string>& in_bag, const BagTopics& requested, const std::string& bag) {
  BagTopics chosen = requested;
  if (chosen.rgb.empty() || chosen.depth.empty()) {
    for (const KnownTopics& k : knownTopics()) {
      const std::string rgb = chosen.rgb.empty() ? k.topics.rgb : chosen.rgb;
      const std::string depth = chosen.depth.empty() ? k.topics.depth : chosen.depth;
      if (!has(in_bag, rgb) || !has(in_bag, depth)) continue;
      chosen.rgb = rgb;
      chosen.depth = depth;
      if (chosen.camera_info.empty() && has(in_bag, k.topics.camera_info)) chosen.camera_info = k.topics.camera_info;
      break;
    }
  }
  core::require(!chosen.rgb.empty() && !chosen.depth.empty(),
                fmt::format("bag '{}' has none of the known colour + depth topic pairs (TUM, OpenNI2, RealSense) and "
                            "--rgb-topic / --depth-topic were not both given; its topics: {}",
                            bag, listed(in_bag)));
  for (const auto& [what, topic] : {std::pair{"colour", chosen.rgb}, std::pair{"depth", chosen.depth},
                                    std::pair{"camera_info", chosen.camera_info}}) {
    if (topic.empty()) continue;
    core::require(has(in_bag, topic), fmt::format("bag '{}' has no {} topic '{}'; its topics: {}", bag, what, topic,
                                                  listed(in_bag)));
  }
  return chosen;
}

}  // namespace amos::rosbag
