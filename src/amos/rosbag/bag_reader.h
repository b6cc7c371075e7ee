#pragma once
// A ROS 1 bag as a frame source for the SLAM loop: io::SequenceReader over the bag's index, whose frames are
// decoded from the bag's messages instead of files. So a bag is read exactly as a folder is: in order, as fast as
// the consumer takes the frames, `prefetch` frames ahead in the reader's thread, nothing dropped; a frame whose
// images do not fit the settings (size, a blank colour image) is skipped with a warning and counted, or with
// ReaderOptions::strict ends the stream with that error.
#include <memory>

#include "amos/io/dataset.h"
#include "amos/rosbag/bag_index.h"

namespace amos::rosbag {

std::unique_ptr<io::SequenceReader> openBagReader(BagIndex index, const io::ReaderOptions& options);

}  // namespace amos::rosbag
