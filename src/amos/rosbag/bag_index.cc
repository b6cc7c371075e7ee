#include "amos/rosbag/bag_index.h"

#include <fmt/format.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "amos/core/error.h"
#include "amos/io/associate.h"
#include "amos/rosbag/bag_file.h"
#include "amos/rosbag/image_messages.h"

namespace amos::rosbag {

namespace fs = std::filesystem;

namespace {

struct TopicStamps {
  std::vector<double> stamps;
  cv::Size first_size;
};

// Every image message's header stamp on `topic`, each message checked for its type and encoding.
TopicStamps readStamps(const ::rosbag::Bag& reader, const std::string& bag, const std::string& topic,
                       bool (*encoding_read)(const std::string&), const char* accepted) {
  TopicStamps out;
  forEachMessage(reader, bag, topic, [&](const ::rosbag::MessageInstance& m, std::size_t position) {
    const auto image = instantiateOrThrow<sensor_msgs::Image>(m, bag);
    core::require(encoding_read(image->encoding),
                  fmt::format("bag '{}': topic '{}' message {} has encoding '{}'; expected {}", bag, topic, position,
                              image->encoding, accepted));
    if (out.stamps.empty()) out.first_size = cv::Size(static_cast<int>(image->width), static_cast<int>(image->height));
    out.stamps.push_back(stampSeconds(image->header.stamp));
    return true;
  });
  core::require(!out.stamps.empty(), fmt::format("bag '{}': topic '{}' has no message", bag, topic));
  return out;
}

std::string frameName(const std::string& bag, const std::string& topic, double stamp) {
  return fmt::format("{}:{}/{:.6f}.png", bag, topic, stamp);
}

}  // namespace

double stampSeconds(const ros::Time& stamp) { return stamp.toSec(); }

void selectFrames(BagIndex& index, std::size_t first, std::size_t count) {
  auto& frames = index.sequence.frames;
  core::require(first < frames.size(), fmt::format("--first-frame {}: bag '{}' has only {} frames", first, index.bag,
                                                   frames.size()));
  const std::size_t end = count == 0 ? frames.size() : std::min(frames.size(), first + count);
  frames = {frames.begin() + static_cast<std::ptrdiff_t>(first), frames.begin() + static_cast<std::ptrdiff_t>(end)};
  index.messages = {index.messages.begin() + static_cast<std::ptrdiff_t>(first),
                    index.messages.begin() + static_cast<std::ptrdiff_t>(end)};
}

BagTopics bagTopics(const std::string& bag, const BagTopics& requested) {
  ::rosbag::Bag reader;
  openBag(reader, bag);
  return chooseTopics(topicsOf(reader), requested, bag);
}

std::optional<core::CameraIntrinsics> readCameraInfo(const std::string& bag, const std::string& topic) {
  if (topic.empty()) return std::nullopt;
  ::rosbag::Bag reader;
  openBag(reader, bag);
  std::optional<core::CameraIntrinsics> intrinsics;
  forEachMessage(reader, bag, topic, [&](const ::rosbag::MessageInstance& m, std::size_t) {
    intrinsics = cameraIntrinsics(*instantiateOrThrow<sensor_msgs::CameraInfo>(m, bag));
    return false;
  });
  return intrinsics;
}

BagIndex indexBag(const std::string& bag, const BagOptions& options) {
  ::rosbag::Bag reader;
  openBag(reader, bag);
  BagIndex index;
  index.bag = bag;
  index.topics = chooseTopics(topicsOf(reader), options.topics, bag);
  const TopicStamps rgb =
      readStamps(reader, bag, index.topics.rgb, isColourEncoding, "rgb8, bgr8, rgba8, bgra8 or mono8");
  const TopicStamps depth = readStamps(reader, bag, index.topics.depth, isDepthEncoding, "16UC1, mono16 or 32FC1");
  index.image_size = rgb.first_size;
  index.messages = io::associateStamps(rgb.stamps, depth.stamps, options.max_dt);
  core::require(!index.messages.empty(),
                fmt::format("bag '{}': no colour message on '{}' has a depth message on '{}' within {} s", bag,
                            index.topics.rgb, index.topics.depth, options.max_dt));
  io::SequenceIndex& sequence = index.sequence;
  sequence.dir = bag;
  sequence.association.window_s = options.max_dt;
  for (const auto& [i, j] : index.messages) {
    io::AssociatedFrame f;
    f.t_rgb = rgb.stamps[i];
    f.t_depth = depth.stamps[j];
    f.rgb_file = frameName(bag, index.topics.rgb, f.t_rgb);
    f.depth_file = frameName(bag, index.topics.depth, f.t_depth);
    sequence.frames.push_back(std::move(f));
  }
  const fs::path groundtruth = fs::path(bag).parent_path() / "groundtruth.txt";
  if (fs::is_regular_file(groundtruth)) sequence.groundtruth_file = groundtruth.string();
  reader.close();
  index.camera_info = readCameraInfo(bag, index.topics.camera_info);
  return index;
}

}  // namespace amos::rosbag
