#include "amos/api/sequence_bag.h"

#include <fmt/format.h>

#include <memory>

#include "amos/core/error.h"
#ifdef AMOS_HAVE_ROSBAG
#include "amos/rosbag/bag_frames.h"
#include "amos/rosbag/bag_index.h"
#include "amos/rosbag/ground_truth_topic.h"
#endif

namespace amos::api {

#ifdef AMOS_HAVE_ROSBAG

bool bagsAvailable() { return true; }

BagSequence openBagSequence(const std::string& bag, const SequenceOptions& options) {
  rosbag::BagOptions bag_options;
  bag_options.topics = {options.rgb_topic, options.depth_topic, options.camera_info_topic};
  auto index = std::make_shared<const rosbag::BagIndex>(rosbag::indexBag(bag, bag_options));
  BagSequence out;
  out.index = index->sequence;
  out.make_reader = [index]() -> FrameReader {
    auto frames = std::make_shared<rosbag::BagFrames>(index);
    return [frames](std::size_t i) {
      rosbag::BagImages images = frames->read(i);
      const io::AssociatedFrame& entry = frames->index().sequence.frames[i];
      return RgbdImages{std::move(images.bgr), std::move(images.depth), entry.t_rgb, entry.rgb_file,
                        entry.depth_file};
    };
  };
  if (!options.groundtruth_topic.empty()) {
    out.ground_truth = rosbag::takeGroundTruthTopic(
        bag, {options.groundtruth_topic, options.groundtruth_parent_frame, options.groundtruth_child_frame},
        out.index);
  }
  return out;
}

#else

bool bagsAvailable() { return false; }

BagSequence openBagSequence(const std::string& bag, const SequenceOptions&) {
  throw core::Error(fmt::format("amos::SequenceFolder: '{}' is a ROS 1 bag, and this library was built without the "
                                "ROS part (run scripts/install_ros_deps.sh and configure with -DAMOS_WITH_ROS=ON)",
                                bag));
}

#endif

}  // namespace amos::api
