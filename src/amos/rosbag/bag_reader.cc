#include "amos/rosbag/bag_reader.h"

#include <fmt/format.h>
#include <sensor_msgs/Image.h>

#include "amos/core/error.h"
#include "amos/rosbag/bag_file.h"
#include "amos/rosbag/image_messages.h"

namespace amos::rosbag {

namespace {

// One topic's image messages by position, read forward; a position behind the last one read starts the topic
// again (the pairing is one-to-one but need not be monotonic in both topics). Its own open bag: two cursors over
// one bag would each throw away the other's decompressed chunk.
class TopicCursor {
 public:
  TopicCursor(const std::string& bag, std::string topic) : bag_(bag), topic_(std::move(topic)) {
    openBag(reader_, bag);
  }

  sensor_msgs::ImageConstPtr at(std::size_t position) {
    try {
      if (!view_ || position < position_) restart();
      for (; it_ != view_->end(); ++it_, ++position_) {
        if (position_ == position) return instantiateOrThrow<sensor_msgs::Image>(*it_, bag_);
      }
    } catch (const ::rosbag::BagException& e) {
      throw core::Error(fmt::format("bag '{}', topic '{}': {}", bag_, topic_, e.what()));
    }
    throw core::Error(fmt::format("bag '{}': topic '{}' has no message {} (changed since it was indexed?)", bag_,
                                  topic_, position));
  }

 private:
  void restart() {
    view_ = std::make_unique<::rosbag::View>(reader_, ::rosbag::TopicQuery(topic_));
    it_ = view_->begin();
    position_ = 0;
  }

  std::string bag_, topic_;
  ::rosbag::Bag reader_;
  std::unique_ptr<::rosbag::View> view_;
  ::rosbag::View::iterator it_;
  std::size_t position_ = 0;
};

// The reader's frame loader: the i-th indexed frame's two messages, converted and checked as a folder's files are.
// Called from the reader's thread only.
struct BagFrameLoader {
  std::shared_ptr<const BagIndex> index;
  std::shared_ptr<TopicCursor> rgb, depth;

  io::RgbdFrame operator()(const io::AssociatedFrame& entry, const io::ReaderOptions& options, std::size_t i) const {
    const auto [rgb_position, depth_position] = index->messages[i];
    cv::Mat bgr = colourImage(*rgb->at(rgb_position), entry.rgb_file);
    const cv::Mat raw_depth = depthImage(*depth->at(depth_position), entry.depth_file);
    return io::rgbdFrameFromImages(entry, std::move(bgr), raw_depth, options, i);
  }
};

}  // namespace

std::unique_ptr<io::SequenceReader> openBagReader(BagIndex index, const io::ReaderOptions& options) {
  BagFrameLoader loader;
  loader.rgb = std::make_shared<TopicCursor>(index.bag, index.topics.rgb);
  loader.depth = std::make_shared<TopicCursor>(index.bag, index.topics.depth);
  io::SequenceIndex sequence = index.sequence;
  loader.index = std::make_shared<const BagIndex>(std::move(index));
  return std::make_unique<io::SequenceReader>(std::move(sequence), options, loader);
}

}  // namespace amos::rosbag
