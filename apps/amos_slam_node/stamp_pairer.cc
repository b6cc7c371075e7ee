#include "stamp_pairer.h"

#include <cmath>

namespace amos::node {

std::optional<sensor_msgs::ImageConstPtr> StampPairer::match(const sensor_msgs::ImageConstPtr& message, Queue& own,
                                                             Queue& other) {
  const ros::Time stamp = message->header.stamp;
  std::optional<std::size_t> best;
  double best_dt = max_dt_;
  for (std::size_t i = 0; i < other.size(); ++i) {
    const double dt = std::abs((other[i]->header.stamp - stamp).toSec());
    if (dt <= best_dt) {
      best = i;
      best_dt = dt;
    }
  }
  if (!best) {
    own.push_back(message);
    if (own.size() > queue_) own.pop_front();
    return std::nullopt;
  }
  sensor_msgs::ImageConstPtr partner = other[*best];
  other.erase(other.begin(), other.begin() + static_cast<std::ptrdiff_t>(*best) + 1);
  while (!own.empty() && own.front()->header.stamp <= stamp) own.pop_front();
  return partner;
}

std::optional<StampPairer::Pair> StampPairer::addColour(const sensor_msgs::ImageConstPtr& colour) {
  std::lock_guard lock(mutex_);
  if (auto depth = match(colour, colour_, depth_)) return Pair{colour, *depth};
  return std::nullopt;
}

std::optional<StampPairer::Pair> StampPairer::addDepth(const sensor_msgs::ImageConstPtr& depth) {
  std::lock_guard lock(mutex_);
  if (auto colour = match(depth, depth_, colour_)) return Pair{*colour, depth};
  return std::nullopt;
}

}  // namespace amos::node
