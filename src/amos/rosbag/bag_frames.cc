#include "amos/rosbag/bag_frames.h"

#include <fmt/format.h>
#include <sensor_msgs/Image.h>

#include "amos/core/error.h"
#include "amos/rosbag/bag_file.h"
#include "amos/rosbag/image_messages.h"

namespace amos::rosbag {

// One topic's image messages by position, read forward; a position behind the last one read starts the topic
// again (the pairing is one-to-one but need not be monotonic in both topics).
class BagFrames::TopicCursor {
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

BagFrames::BagFrames(std::shared_ptr<const BagIndex> index)
    : index_(std::move(index)),
      rgb_(std::make_unique<TopicCursor>(index_->bag, index_->topics.rgb)),
      depth_(std::make_unique<TopicCursor>(index_->bag, index_->topics.depth)) {}
BagFrames::~BagFrames() = default;
BagFrames::BagFrames(BagFrames&&) noexcept = default;
BagFrames& BagFrames::operator=(BagFrames&&) noexcept = default;

BagImages BagFrames::read(std::size_t i) {
  core::require(i < index_->messages.size(),
                fmt::format("bag '{}': no frame {} (it has {})", index_->bag, i, index_->messages.size()));
  const auto [rgb_position, depth_position] = index_->messages[i];
  const io::AssociatedFrame& entry = index_->sequence.frames[i];
  return {colourImage(*rgb_->at(rgb_position), entry.rgb_file), depthImage(*depth_->at(depth_position),
                                                                           entry.depth_file)};
}

}  // namespace amos::rosbag
