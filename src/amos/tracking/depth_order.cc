#include "amos/tracking/depth_order.h"

#include <algorithm>

namespace amos::tracking {

std::vector<std::pair<float, int>> keypointsByDepth(const map::FrameFeatures& f) {
  std::vector<std::pair<float, int>> by_depth;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] > 0) by_depth.emplace_back(f.depth[i], static_cast<int>(i));
  }
  std::sort(by_depth.begin(), by_depth.end());
  return by_depth;
}

}  // namespace amos::tracking
