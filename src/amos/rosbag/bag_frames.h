#pragma once
// An indexed bag's frames by number: the colour and depth messages of frame i (bag_index.h), decoded as
// image_messages.h does. Each topic is read forward by a view of its own over an open bag of its own (two cursors
// over one bag would each throw away the other's decompressed chunk), so reading the frames in order is one pass;
// a frame behind the last one read starts its topics again. Not thread-safe: one per thread.
#include <opencv2/core.hpp>

#include <memory>
#include <string>

#include "amos/rosbag/bag_index.h"

namespace amos::rosbag {

struct BagImages {
  cv::Mat bgr;    // CV_8UC3
  cv::Mat depth;  // CV_16U raw units or CV_32F metres, as the topic's encoding (image_messages.h)
};

class BagFrames {
 public:
  explicit BagFrames(std::shared_ptr<const BagIndex> index);
  ~BagFrames();
  BagFrames(BagFrames&&) noexcept;
  BagFrames& operator=(BagFrames&&) noexcept;

  const BagIndex& index() const { return *index_; }
  // Frame i's images; throws core::Error naming the bag, the topic and the message (a damaged chunk, a message of
  // another encoding) or i out of range.
  BagImages read(std::size_t i);

 private:
  class TopicCursor;
  std::shared_ptr<const BagIndex> index_;
  std::unique_ptr<TopicCursor> rgb_, depth_;
};

}  // namespace amos::rosbag
