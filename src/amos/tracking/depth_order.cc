#include "amos/tracking/depth_order.h"

#include <algorithm>

namespace amos::tracking {

std::vector<std::pair<float, int>> keypointsByDepth(const map::FrameFeatures& f, double close_depth, int min_count) {
  std::vector<std::pair<float, int>> by_depth;
  std::size_t close = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] <= 0) continue;
    by_depth.emplace_back(f.depth[i], static_cast<int>(i));
    close += static_cast<double>(f.depth[i]) <= close_depth;
  }
  // (depth, index) pairs are all different, so the sorted prefix is the same as that of a full sort.
  const std::size_t wanted = std::max(close, static_cast<std::size_t>(std::max(min_count, 0))) + 1;
  const std::size_t keep = std::min(by_depth.size(), wanted);
  std::partial_sort(by_depth.begin(), by_depth.begin() + static_cast<std::ptrdiff_t>(keep), by_depth.end());
  by_depth.resize(keep);
  return by_depth;
}

}  // namespace amos::tracking
