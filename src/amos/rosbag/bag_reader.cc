#include "amos/rosbag/bag_reader.h"

#include "amos/rosbag/bag_frames.h"

namespace amos::rosbag {

std::unique_ptr<io::SequenceReader> openBagReader(BagIndex index, const io::ReaderOptions& options) {
  io::SequenceIndex sequence = index.sequence;
  // The reader's frame loader, called from the reader's thread only: the i-th indexed frame's two messages,
  // converted and checked as a folder's files are.
  auto frames = std::make_shared<BagFrames>(std::make_shared<const BagIndex>(std::move(index)));
  auto loader = [frames](const io::AssociatedFrame& entry, const io::ReaderOptions& reader, std::size_t i) {
    BagImages images = frames->read(i);
    return io::rgbdFrameFromImages(entry, std::move(images.bgr), images.depth, reader, i);
  };
  return std::make_unique<io::SequenceReader>(std::move(sequence), options, loader);
}

}  // namespace amos::rosbag
