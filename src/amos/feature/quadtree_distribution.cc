#include "amos/feature/quadtree_distribution.h"

#include <algorithm>
#include <cmath>

namespace amos::feature {

namespace {

// A rectangle of the region and the keypoints inside it: order[begin, end).
struct Node {
  float x0, y0, x1, y1;
  int begin, end;
  int count() const { return end - begin; }
  // Nodes below a pixel cannot separate integer-pixel keypoints any further.
  bool splittable() const { return count() > 1 && (x1 - x0 > 1.0f || y1 - y0 > 1.0f); }
};

class Quadtree {
 public:
  Quadtree(const std::vector<cv::KeyPoint>& keypoints, const cv::Rect2f& region) : region_(region) {
    const size_t n = keypoints.size();
    order_.resize(n);
    xs_.resize(n);
    ys_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      order_[i] = static_cast<int>(i);
      xs_[i] = std::clamp(keypoints[i].pt.x, region.x, region.x + region.width);
      ys_[i] = std::clamp(keypoints[i].pt.y, region.y, region.y + region.height);
    }
  }

  // Initial nodes: about square columns over the region (one node for a 4:3 image).
  std::vector<Node> rootNodes() {
    const int columns = std::max(1, static_cast<int>(std::lround(region_.width / std::max(region_.height, 1.0f))));
    std::vector<Node> nodes;
    int begin = 0;
    for (int c = 0; c < columns; ++c) {
      const float x0 = region_.x + region_.width * c / columns;
      const float x1 = c + 1 == columns ? region_.x + region_.width + 1 : region_.x + region_.width * (c + 1) / columns;
      const int end = partition(begin, static_cast<int>(order_.size()), [&](int i) { return xs_[i] < x1; });
      if (end > begin) nodes.push_back({x0, region_.y, x1, region_.y + region_.height, begin, end});
      begin = end;
    }
    return nodes;
  }

  // Appends the non-empty quadrants of `node` to `out` (top-left, top-right, bottom-left, bottom-right).
  void split(const Node& node, std::vector<Node>& out) {
    const float xm = 0.5f * (node.x0 + node.x1), ym = 0.5f * (node.y0 + node.y1);
    const int mid_x = partition(node.begin, node.end, [&](int i) { return xs_[i] < xm; });
    const int mid_left = partition(node.begin, mid_x, [&](int i) { return ys_[i] < ym; });
    const int mid_right = partition(mid_x, node.end, [&](int i) { return ys_[i] < ym; });
    const Node children[4] = {{node.x0, node.y0, xm, ym, node.begin, mid_left},
                              {xm, node.y0, node.x1, ym, mid_x, mid_right},
                              {node.x0, ym, xm, node.y1, mid_left, mid_x},
                              {xm, ym, node.x1, node.y1, mid_right, node.end}};
    for (const Node& child : children)
      if (child.count() > 0) out.push_back(child);
  }

  const std::vector<int>& order() const { return order_; }

 private:
  // The order inside a node does not matter: node membership is geometric and ties are broken by index.
  template <typename Pred>
  int partition(int begin, int end, Pred pred) {
    return static_cast<int>(std::partition(order_.begin() + begin, order_.begin() + end, pred) - order_.begin());
  }

  cv::Rect2f region_;
  std::vector<int> order_;
  std::vector<float> xs_, ys_;
};

}  // namespace

std::vector<int> distributeQuadtree(const std::vector<cv::KeyPoint>& keypoints, const cv::Rect2f& region, int target) {
  std::vector<int> kept;
  if (keypoints.empty() || target <= 0) return kept;
  Quadtree tree(keypoints, region);
  std::vector<Node> nodes = tree.rootNodes();

  while (static_cast<int>(nodes.size()) < target) {
    std::vector<Node> next, to_split;
    for (const Node& node : nodes) (node.splittable() ? to_split : next).push_back(node);
    if (to_split.empty()) break;
    if (static_cast<int>(nodes.size() + 3 * to_split.size()) < target) {
      // Far from the target: split every node that can be split.
      for (const Node& node : to_split) tree.split(node, next);
      nodes = std::move(next);
      continue;
    }
    // Close to the target: split the most populated nodes first and stop as soon as it is reached.
    std::stable_sort(to_split.begin(), to_split.end(),
                     [](const Node& a, const Node& b) { return a.count() > b.count(); });
    size_t k = 0;
    while (k < to_split.size() && static_cast<int>(next.size() + (to_split.size() - k)) < target)
      tree.split(to_split[k++], next);
    next.insert(next.end(), to_split.begin() + static_cast<std::ptrdiff_t>(k), to_split.end());
    nodes = std::move(next);
  }

  // The strongest keypoint of each node (ties: lower index).
  const std::vector<int>& order = tree.order();
  for (const Node& node : nodes) {
    int best = order[static_cast<size_t>(node.begin)];
    for (int j = node.begin + 1; j < node.end; ++j) {
      const int i = order[static_cast<size_t>(j)];
      const float r = keypoints[static_cast<size_t>(i)].response, rb = keypoints[static_cast<size_t>(best)].response;
      if (r > rb || (r == rb && i < best)) best = i;
    }
    kept.push_back(best);
  }
  std::sort(kept.begin(), kept.end(), [&](int a, int b) {
    const float ra = keypoints[static_cast<size_t>(a)].response, rb = keypoints[static_cast<size_t>(b)].response;
    return ra > rb || (ra == rb && a < b);
  });
  if (static_cast<int>(kept.size()) > target) kept.resize(static_cast<size_t>(target));
  return kept;
}

}  // namespace amos::feature
