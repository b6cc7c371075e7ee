#include "amos/run/bag_source.h"

#include <fmt/format.h>

#include <filesystem>

#include "amos/core/error.h"
#include "amos/run/sequence_run.h"
#include "amos/run/settings_sections.h"
#ifdef AMOS_HAVE_ROSBAG
#include "amos/rosbag/bag_index.h"
#include "amos/rosbag/bag_reader.h"
#include "amos/rosbag/bag_settings.h"
#include "amos/rosbag/ground_truth_topic.h"
#endif

namespace amos::run {

bool isBagFile(const std::string& sequence) {
  const std::filesystem::path path(sequence);
  return path.extension() == ".bag" && std::filesystem::is_regular_file(path);
}

#ifdef AMOS_HAVE_ROSBAG

namespace {

rosbag::BagTopics requestedTopics(const SequenceRunOptions& options) {
  return {options.rgb_topic, options.depth_topic, options.camera_info_topic};
}

}  // namespace

config::Settings loadBagSettings(const std::string& path, const SequenceRunOptions& options) {
  const rosbag::BagTopics topics = rosbag::bagTopics(options.sequence_dir, requestedTopics(options));
  const std::string source = topics.camera_info.empty()
                                 ? fmt::format("bag '{}'", options.sequence_dir)
                                 : fmt::format("bag '{}', topic '{}'", options.sequence_dir, topics.camera_info);
  return rosbag::settingsForBag(path, rosbag::readCameraInfo(options.sequence_dir, topics.camera_info), source,
                                settingsSections());
}

BagInput indexBagInput(const SequenceRunOptions& options, const config::Settings& settings) {
  rosbag::BagOptions bag_options;
  bag_options.topics = requestedTopics(options);
  rosbag::BagIndex index = rosbag::indexBag(options.sequence_dir, bag_options);
  const cv::Size size = index.image_size;
  core::require(size.width == settings.camera.width && size.height == settings.camera.height,
                fmt::format("Camera.width x Camera.height is {}x{} in {}, but bag '{}' has {}x{} images on '{}': set "
                            "them (and the intrinsics) for the camera that recorded it",
                            settings.camera.width, settings.camera.height,
                            options.config_label.empty() ? "the settings" : options.config_label, index.bag,
                            size.width, size.height, index.topics.rgb));
  rosbag::selectFrames(index, options.first_frame, options.max_frames);
  BagInput input;
  if (!options.groundtruth_topic.empty()) {
    input.ground_truth = rosbag::takeGroundTruthTopic(
        index.bag, {options.groundtruth_topic, options.groundtruth_parent_frame, options.groundtruth_child_frame},
        index.sequence);
    input.ground_truth_source = fmt::format("bag '{}', topic '{}'", index.bag, options.groundtruth_topic);
  }
  input.index = index.sequence;
  auto shared = std::make_shared<rosbag::BagIndex>(std::move(index));
  input.open = [shared](const io::ReaderOptions& reader) { return rosbag::openBagReader(std::move(*shared), reader); };
  return input;
}

#else

namespace {

[[noreturn]] void noRos(const std::string& bag) {
  throw core::Error(fmt::format("--sequence {}: this build reads no ROS bags (run scripts/install_ros_deps.sh and "
                                "configure with -DAMOS_WITH_ROS=ON)",
                                bag));
}

}  // namespace

config::Settings loadBagSettings(const std::string&, const SequenceRunOptions& options) { noRos(options.sequence_dir); }
BagInput indexBagInput(const SequenceRunOptions& options, const config::Settings&) { noRos(options.sequence_dir); }

#endif

}  // namespace amos::run
