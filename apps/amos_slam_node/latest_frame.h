#pragma once
// The hand-over from the subscription callbacks to the tracking thread: one frame waits at most, a newer one
// replaces it and the older one is counted as dropped (as `run --realtime` drops frames when SLAM falls behind).
// The tracking thread blocks on a condition variable; close() ends the stream.
#include <opencv2/core.hpp>
#include <ros/time.h>

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <optional>

namespace amos::node {

struct StampedFrame {
  cv::Mat bgr, depth;  // as amos::Slam::track takes them
  ros::Time stamp;     // the colour image's header stamp
  double timestamp = 0;  // the same, as the folder reader's double (rosbag::stampSeconds)
  std::chrono::steady_clock::time_point arrival;  // when the pair was complete here
};

class LatestFrame {
 public:
  // Makes `frame` the waiting one; false once closed.
  bool put(StampedFrame frame);
  // Blocks until a frame waits (it is returned) or the slot is closed and empty (nullopt).
  std::optional<StampedFrame> take();
  void close();
  std::size_t received() const;
  std::size_t dropped() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::optional<StampedFrame> waiting_;
  bool closed_ = false;
  std::size_t received_ = 0, dropped_ = 0;
};

}  // namespace amos::node
