#include "amos/eval/associate.h"

#include <algorithm>

#include "amos/io/associate.h"

namespace amos::eval {

std::vector<std::pair<std::size_t, std::size_t>> associate(const std::vector<double>& first,
                                                           const std::vector<double>& second,
                                                           const AssociationOptions& options) {
  return io::associateStamps(first, second, options.max_difference_s, options.offset_s);
}

std::vector<io::StampedPose> sortedUniqueByTimestamp(const std::vector<io::StampedPose>& poses) {
  std::vector<io::StampedPose> sorted = poses;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const io::StampedPose& x, const io::StampedPose& y) { return x.timestamp < y.timestamp; });
  std::vector<io::StampedPose> unique;
  unique.reserve(sorted.size());
  for (const io::StampedPose& pose : sorted) {
    if (!unique.empty() && unique.back().timestamp == pose.timestamp) {
      unique.back() = pose;  // stable sort keeps file order among equal stamps: the last one wins
    } else {
      unique.push_back(pose);
    }
  }
  return unique;
}

std::vector<double> timestampsOf(const std::vector<io::StampedPose>& poses) {
  std::vector<double> stamps;
  stamps.reserve(poses.size());
  for (const io::StampedPose& pose : poses) stamps.push_back(pose.timestamp);
  return stamps;
}

}  // namespace amos::eval
