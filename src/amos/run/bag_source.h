#pragma once
// A ROS 1 bag as a run's sequence (`run --sequence X.bag`): its settings (the calibration from its camera_info when
// the settings file leaves it out, rosbag/bag_settings.h), its frames and its frame source (rosbag/). Without the
// ROS part in the build (AMOS_WITH_ROS) every function but isBagFile throws core::Error saying so.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/io/dataset.h"
#include "amos/io/frame_source.h"
#include "amos/io/trajectory.h"

namespace amos::run {

struct SequenceRunOptions;

// A regular file whose name ends in ".bag".
bool isBagFile(const std::string& sequence);

// The settings file read for a run over the bag options.sequence_dir (settings_sections' sections).
config::Settings loadBagSettings(const std::string& path, const SequenceRunOptions& options);

// The bag's frames (after --first-frame and --max-frames), how to open them as the run's source, and the ground
// truth from --groundtruth-topic (which wins over a groundtruth.txt beside the bag: index.groundtruth_file is then
// "").
struct BagInput {
  io::SequenceIndex index;
  std::function<std::unique_ptr<io::FrameSource>(const io::ReaderOptions&)> open;
  std::vector<io::StampedPose> ground_truth;  // from the topic (empty without one)
  std::string ground_truth_source;            // "bag 'X', topic 'T'" (for messages)
};
// Throws core::Error naming the bag as rosbag::indexBag does, and when its images are not Camera.width x height;
// naming the bag and the topic as rosbag::readGroundTruthTopic does.
BagInput indexBagInput(const SequenceRunOptions& options, const config::Settings& settings);

}  // namespace amos::run
