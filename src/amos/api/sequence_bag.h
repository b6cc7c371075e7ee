#pragma once
// amos::SequenceFolder over a ROS 1 bag (include/amos/sequence_folder.h): the rosbag module's index (topics,
// pairing by stamp, ground truth from groundtruth.txt or a topic) and frames, the ones `amos-slam run --sequence
// X.bag` reads. In a library built without the ROS part (AMOS_WITH_ROS) openBagSequence throws an error naming the
// bag and saying so.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "amos/io/dataset.h"
#include "amos/io/trajectory.h"
#include "amos/sequence_folder.h"

namespace amos::api {

// Frame i of a sequence; one such reader per thread (a bag's readers hold cursors of their own).
using FrameReader = std::function<RgbdImages(std::size_t)>;

struct BagSequence {
  io::SequenceIndex index;                                // frames named "<bag>:<topic>/<stamp>.png"
  std::function<FrameReader()> make_reader;               // a new reader (for read(i), for next()'s thread)
  std::optional<std::vector<io::StampedPose>> ground_truth;  // from SequenceOptions::groundtruth_topic
};

bool bagsAvailable();
// Throws std::runtime_error naming the bag (and topic) as `run --sequence X.bag` does.
BagSequence openBagSequence(const std::string& bag, const SequenceOptions& options);

}  // namespace amos::api
