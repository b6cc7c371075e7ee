#pragma once
// Pairs colour and depth images by header stamp as they arrive, for the lowest latency: a message is paired at
// once with the other topic's waiting message nearest in time, if that is within max_dt, and everything older on
// both topics is then let go; otherwise it waits (at most `queue` per topic, the oldest let go first).
// message_filters' ApproximateTime would pick globally better pairs, but holds each pair back until the next
// messages arrive (a frame period of latency). With colour and depth a few ms apart and frames 33 ms apart (the
// TUM, Bonn and OpenNI2 cameras) the nearest waiting message is the right one. Thread-safe.
#include <sensor_msgs/Image.h>

#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>

namespace amos::node {

class StampPairer {
 public:
  using Pair = std::pair<sensor_msgs::ImageConstPtr, sensor_msgs::ImageConstPtr>;  // colour, depth
  StampPairer(std::size_t queue, double max_dt) : queue_(queue == 0 ? 1 : queue), max_dt_(max_dt) {}

  std::optional<Pair> addColour(const sensor_msgs::ImageConstPtr& colour);
  std::optional<Pair> addDepth(const sensor_msgs::ImageConstPtr& depth);

 private:
  using Queue = std::deque<sensor_msgs::ImageConstPtr>;
  // `message` against the other topic's waiting messages: the nearest within max_dt (removed with the older ones
  // of both queues), else `message` waits in `own`.
  std::optional<sensor_msgs::ImageConstPtr> match(const sensor_msgs::ImageConstPtr& message, Queue& own,
                                                  Queue& other);

  std::mutex mutex_;
  Queue colour_, depth_;  // guarded by mutex_, oldest first
  std::size_t queue_;
  double max_dt_;
};

}  // namespace amos::node
