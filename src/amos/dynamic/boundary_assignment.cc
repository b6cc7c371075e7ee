#include "amos/dynamic/boundary_assignment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>
#include <utility>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/dynamic/robust_scale.h"

namespace amos::dynamic {

void BoundaryOptions::check() const {
  core::requireAtLeast(search_radius_px, "search_radius_px", 0);
  core::requireAtLeast(border_margin_px, "border_margin_px", 0);
}

std::vector<bool> borderSuperpixels(const cv::Mat& superpixel_labels, int count, int margin_px) {
  core::require(superpixel_labels.type() == CV_32S, "borderSuperpixels: labels must be CV_32S");
  core::require(margin_px >= 0, "borderSuperpixels: margin must be >= 0");
  std::vector<bool> border(std::max(0, count), false);
  const int w = superpixel_labels.cols, h = superpixel_labels.rows;
  const int m = std::min(margin_px, std::max(0, std::min(w, h) / 2 - 1));
  auto mark = [&](const int* row, int x0, int x1) {
    for (int x = std::max(0, x0); x < std::min(w, x1); ++x) {
      const int label = row[x];
      if (label < 0 || label >= count) throw core::Error("borderSuperpixels: label out of range");
      border[label] = true;
    }
  };
  // Only the band within m + 1 pixels of the image edge is visited.
  for (int y = 0; y < h; ++y) {
    const int* row = superpixel_labels.ptr<int>(y);
    if (y <= m || y >= h - 1 - m) {
      mark(row, 0, w);
    } else {
      mark(row, 0, m + 1);
      mark(row, std::max(m + 1, w - 1 - m), w);
    }
  }
  return border;
}

cv::Mat decisionClusterMap(const cv::Mat& cluster_map, const cv::Mat& superpixel_labels,
                           const std::vector<bool>& border_superpixels) {
  core::require(cluster_map.type() == CV_32S && superpixel_labels.type() == CV_32S &&
                    cluster_map.size() == superpixel_labels.size(),
                "decisionClusterMap: both maps must be CV_32S of the same size");
  // Bytes instead of vector<bool>'s bits: this is looked up for every pixel.
  const std::vector<unsigned char> border(border_superpixels.begin(), border_superpixels.end());
  const auto count = static_cast<unsigned>(border.size());
  cv::Mat out = cluster_map.clone();
  for (int y = 0; y < out.rows; ++y) {
    const int* sp = superpixel_labels.ptr<int>(y);
    int* o = out.ptr<int>(y);
    for (int x = 0; x < out.cols; ++x) {
      const auto label = static_cast<unsigned>(sp[x]);
      if (label >= count) throw core::Error("decisionClusterMap: superpixel label out of range");
      if (border[label]) o[x] = -1;
    }
  }
  return out;
}

int assignToNeighbourCluster(cv::Point2f p, const cv::Mat& decision_map, const std::vector<double>& cluster_error,
                             int radius_px) {
  core::require(decision_map.type() == CV_32S, "assignToNeighbourCluster: map must be CV_32S");
  const int px = static_cast<int>(std::lround(p.x)), py = static_cast<int>(std::lround(p.y));
  const int own =
      (px >= 0 && py >= 0 && px < decision_map.cols && py < decision_map.rows) ? decision_map.at<int>(py, px) : -1;
  auto error_of = [&](int c) { return c >= 0 && c < static_cast<int>(cluster_error.size()) ? cluster_error[c] : 0.0; };
  int best = own;
  double best_error = own >= 0 ? error_of(own) : -1.0;
  const int r2 = radius_px * radius_px;
  const int y0 = std::max(0, py - radius_px), y1 = std::min(decision_map.rows - 1, py + radius_px);
  for (int y = y0; y <= y1; ++y) {
    const int dy = y - py;
    const int half = static_cast<int>(std::sqrt(static_cast<double>(std::max(0, r2 - dy * dy))));
    const int x0 = std::max(0, px - half), x1 = std::min(decision_map.cols - 1, px + half);
    const int* row = decision_map.ptr<int>(y);
    for (int x = x0; x <= x1; ++x) {
      const int c = row[x];
      if (c < 0 || c == best) continue;
      const double e = error_of(c);
      // Strictly larger wins; equal errors keep the point's own cluster, else the lower id.
      if (e > best_error || (e == best_error && best != own && (best < 0 || c < best))) best = c, best_error = e;
    }
  }
  return best;
}

namespace {

// Index of b in list, or -1. Lists are short (a superpixel has ~6 neighbours), so a linear scan beats anything.
int findIn(const std::vector<int>& list, int b) {
  for (std::size_t i = 0; i < list.size(); ++i)
    if (list[i] == b) return static_cast<int>(i);
  return -1;
}

// Calls visit(a, b, x_a, y_a, x_b, y_b) for every pair of 4-neighbouring pixels with different labels a != b.
template <typename Visit>
void forEachLabelChange(const cv::Mat& labels, Visit&& visit) {
  const int w = labels.cols, h = labels.rows;
  for (int y = 0; y < h; ++y) {
    const int* row = labels.ptr<int>(y);
    const int* below = y + 1 < h ? labels.ptr<int>(y + 1) : nullptr;
    for (int x = 0; x < w; ++x) {
      const int a = row[x];
      if (x + 1 < w && a != row[x + 1]) visit(a, row[x + 1], x, y, x + 1, y);
      if (below && a != below[x]) visit(a, below[x], x, y, x, y + 1);
    }
  }
}

}  // namespace

std::vector<std::vector<int>> superpixelNeighbours(const cv::Mat& labels, int count) {
  core::require(labels.type() == CV_32S, "superpixelNeighbours: labels must be CV_32S");
  std::vector<std::vector<int>> neighbours(std::max(0, count));
  int last_a = -1, last_b = -1;  // runs of pixels along one border repeat the same pair
  forEachLabelChange(labels, [&](int a, int b, int, int, int, int) {
    if (a == last_a && b == last_b) return;
    last_a = a, last_b = b;
    if (a < 0 || b < 0 || a >= count || b >= count) throw core::Error("superpixelNeighbours: label out of range");
    if (findIn(neighbours[a], b) >= 0) return;
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  });
  for (auto& list : neighbours) std::sort(list.begin(), list.end());
  return neighbours;
}

namespace {

// Border pixel pairs with known depth on both sides, and how many of them are depth steps, per neighbour slot.
class OcclusionCounter {
 public:
  OcclusionCounter(const std::vector<std::vector<int>>& neighbours, const cv::Mat& depth, double ratio)
      : neighbours_(neighbours), depth_(depth), ratio_(static_cast<float>(ratio)) {
    const std::size_t count = neighbours.size();
    pairs_.resize(count), steps_.resize(count);
    for (std::size_t a = 0; a < count; ++a)
      pairs_[a].assign(neighbours[a].size(), 0), steps_[a].assign(neighbours[a].size(), 0);
  }

  // The full-resolution pixels (xa, ya) of label a and (xb, yb) of label b, 4-neighbours.
  void add(int a, int b, int xa, int ya, int xb, int yb) {
    // The label map may come from a lower working resolution, so its border can sit a pixel or two off the depth
    // step: compare depths two pixels away on either side (along the row or the column the pair lies on).
    constexpr int kReach = 2;
    const int w = depth_.cols, h = depth_.rows;
    const int dx = xb - xa, dy = yb - ya;
    const int xa2 = std::max(0, xa - dx * (kReach - 1)), ya2 = std::max(0, ya - dy * (kReach - 1));
    const int xb2 = std::min(w - 1, xb + dx * (kReach - 1)), yb2 = std::min(h - 1, yb + dy * (kReach - 1));
    const float za = depth_.ptr<float>(ya2)[xa2], zb = depth_.ptr<float>(yb2)[xb2];
    if (!(za > 0.f) || !(zb > 0.f)) return;  // unknown (or NaN) depth: no say
    // The scan alternates between the pair across a column border and the pair across a row border: one
    // remembered pair (and its neighbour slots) for each direction.
    Slots& c = cached_[dy != 0 ? 1 : 0];
    if (a != c.a || b != c.b) {
      const int count = static_cast<int>(neighbours_.size());
      if (a < 0 || b < 0 || a >= count || b >= count) throw core::Error("occlusionEdges: label out of range");
      c.slot_a = findIn(neighbours_[a], b), c.slot_b = findIn(neighbours_[b], a);
      if (c.slot_a < 0 || c.slot_b < 0) throw core::Error("occlusionEdges: neighbours do not match the labels");
      c.a = a, c.b = b;
    }
    const bool step = std::fabs(za - zb) > ratio_ * std::min(za, zb);
    ++pairs_[a][c.slot_a], ++pairs_[b][c.slot_b];
    if (step) ++steps_[a][c.slot_a], ++steps_[b][c.slot_b];
  }

  std::vector<std::vector<bool>> occluding() const {
    std::vector<std::vector<bool>> out(neighbours_.size());
    for (std::size_t a = 0; a < neighbours_.size(); ++a) {
      out[a].resize(neighbours_[a].size());
      for (std::size_t k = 0; k < neighbours_[a].size(); ++k) out[a][k] = 2 * steps_[a][k] > pairs_[a][k];
    }
    return out;
  }

 private:
  const std::vector<std::vector<int>>& neighbours_;
  const cv::Mat& depth_;
  float ratio_;
  std::vector<std::vector<int>> pairs_, steps_;
  struct Slots {
    int a = -1, b = -1, slot_a = -1, slot_b = -1;
  };
  Slots cached_[2];
};

}  // namespace

std::vector<std::vector<bool>> occlusionEdges(const cv::Mat& labels, const std::vector<std::vector<int>>& neighbours,
                                              const cv::Mat& depth, double ratio) {
  core::require(labels.type() == CV_32S && depth.type() == CV_32F && depth.size() == labels.size(),
                "occlusionEdges: labels CV_32S and depth CV_32F of the same size");
  OcclusionCounter counter(neighbours, depth, ratio);
  forEachLabelChange(labels, [&](int a, int b, int xa, int ya, int xb, int yb) { counter.add(a, b, xa, ya, xb, yb); });
  return counter.occluding();
}

std::vector<std::vector<bool>> occlusionEdgesOfBlocks(const cv::Mat& block_labels, int factor,
                                                      const std::vector<std::vector<int>>& neighbours,
                                                      const cv::Mat& depth, double ratio) {
  core::require(factor >= 1 && block_labels.type() == CV_32S && depth.type() == CV_32F &&
                    depth.cols == factor * block_labels.cols && depth.rows == factor * block_labels.rows,
                "occlusionEdgesOfBlocks: labels CV_32S, depth CV_32F of factor times their size");
  // A label change between two blocks is a change between the facing pixels of every row (or column) of them,
  // and the blocks hold no change inside: the same pairs as a scan of the upsampled map, a factor^2 fewer pixels.
  OcclusionCounter counter(neighbours, depth, ratio);
  const int f = factor;
  forEachLabelChange(block_labels, [&](int a, int b, int xa, int ya, int xb, int yb) {
    if (yb == ya) {  // side by side: the pairs along the shared column border
      for (int r = 0; r < f; ++r) counter.add(a, b, f * xa + f - 1, f * ya + r, f * xb, f * yb + r);
    } else {  // one above the other
      for (int c = 0; c < f; ++c) counter.add(a, b, f * xa + c, f * ya + f - 1, f * xb + c, f * yb);
    }
  });
  return counter.occluding();
}

double superpixelDissimilarity(const Superpixel& a, const Superpixel& b, double colour_scale, double depth_scale_m) {
  const double dl = a.L - b.L, da = a.A - b.A, db = a.B - b.B;
  double d = std::sqrt(dl * dl + da * da + db * db) / colour_scale;
  if (a.depth > 0 && b.depth > 0) d += std::fabs(a.depth - b.depth) / depth_scale_m;
  return d;
}

std::vector<RegionLabel> growRegions(const std::vector<Superpixel>& superpixels,
                                     const std::vector<std::vector<int>>& neighbours, std::vector<RegionLabel> labels,
                                     const std::vector<bool>& may_be_dynamic, double colour_scale,
                                     double depth_scale_m, const std::vector<std::vector<bool>>& occluding) {
  const std::size_t n = superpixels.size();
  core::require(neighbours.size() == n && labels.size() == n && may_be_dynamic.size() == n,
                "growRegions: superpixels, neighbours, seeds and flags differ in number");
  core::require(occluding.empty() || occluding.size() == n, "growRegions: occlusion flags differ in number");
  core::require(colour_scale > 0 && depth_scale_m > 0, "growRegions: scales must be positive");
  // (cost, superpixel to label, label offered): the cheapest offer is taken first.
  using Offer = std::tuple<double, int, int>;
  std::priority_queue<Offer, std::vector<Offer>, std::greater<Offer>> offers;
  auto offerFrom = [&](int a) {
    const RegionLabel l = labels[a];
    for (std::size_t k = 0; k < neighbours[a].size(); ++k) {
      const int b = neighbours[a][k];
      if (labels[b] != RegionLabel::kUnlabelled) continue;
      if (l == RegionLabel::kDynamic && (!may_be_dynamic[b] || (!occluding.empty() && occluding[a][k]))) continue;
      const double cost = superpixelDissimilarity(superpixels[a], superpixels[b], colour_scale, depth_scale_m);
      offers.emplace(cost, b, static_cast<int>(l));
    }
  };
  for (std::size_t a = 0; a < n; ++a)
    if (labels[a] != RegionLabel::kUnlabelled) offerFrom(static_cast<int>(a));
  while (!offers.empty()) {
    const auto [cost, b, l] = offers.top();
    offers.pop();
    if (labels[b] != RegionLabel::kUnlabelled) continue;
    labels[b] = static_cast<RegionLabel>(l);
    offerFrom(b);
  }
  for (RegionLabel& l : labels)
    if (l == RegionLabel::kUnlabelled) l = RegionLabel::kStatic;
  return labels;
}

std::vector<RegionLabel> seedSuperpixels(const SuperpixelSegmentation& segmentation,
                                         const std::vector<std::vector<int>>& neighbours,
                                         const std::vector<bool>& border, const std::vector<bool>& dynamic_cluster,
                                         const std::vector<TrackEvidence>& tracks, const SeedBars& bars,
                                         const SeedOptions& options) {
  const cv::Mat& labels = segmentation.labels;
  const std::vector<Superpixel>& superpixels = segmentation.superpixels;
  const double static_px = bars.static_px, epipolar_px = bars.epipolar_px;
  const int n = static_cast<int>(superpixels.size());
  const int clusters = static_cast<int>(dynamic_cluster.size());
  core::require(labels.type() == CV_32S, "seedSuperpixels: labels must be CV_32S");
  core::require(static_cast<int>(neighbours.size()) == n && static_cast<int>(border.size()) == n,
                "seedSuperpixels: superpixels, neighbours and border flags differ in number");
  auto clusterOf = [&](int s) {
    const int c = superpixels[s].cluster;
    if (c < 0 || c >= clusters) throw core::Error("seedSuperpixels: superpixel without a valid cluster");
    return c;
  };
  // Dynamic clusters bordering each cluster.
  std::vector<std::vector<int>> dynamic_near(clusters);
  for (int a = 0; a < n; ++a)
    for (int b : neighbours[a]) {
      const int ca = clusterOf(a), cb = clusterOf(b);
      if (ca != cb && dynamic_cluster[cb]) dynamic_near[ca].push_back(cb);
    }
  for (auto& list : dynamic_near) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  auto superpixelAt = [&](cv::Point2f p) {
    const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
    if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) return -1;
    return labels.at<int>(y, x);
  };
  // The motion of each dynamic cluster: the component-wise median of its tracks' residuals.
  std::vector<std::vector<double>> rx(clusters), ry(clusters);
  for (const TrackEvidence& t : tracks) {
    const int s = superpixelAt(t.pixel);
    if (s < 0 || border[s] || !t.residual) continue;
    const int c = clusterOf(s);
    if (!dynamic_cluster[c]) continue;
    rx[c].push_back(t.residual->x());
    ry[c].push_back(t.residual->y());
  }
  std::vector<std::optional<Eigen::Vector2d>> motion(clusters);
  for (int c = 0; c < clusters; ++c) {
    if (rx[c].empty()) continue;
    const Eigen::Vector2d m(upperMedian(std::move(rx[c])), upperMedian(std::move(ry[c])));
    if (m.norm() >= static_px) motion[c] = m;
  }
  std::vector<int> dynamic_votes(n, 0), static_votes(n, 0);
  std::vector<bool> in_zone(n, false);
  for (const TrackEvidence& t : tracks) {
    const int s = superpixelAt(t.pixel);
    if (s < 0 || border[s]) continue;
    const int c = clusterOf(s);
    const std::vector<int> own{c};
    const std::vector<int>& zone = dynamic_cluster[c] ? own : dynamic_near[c];
    in_zone[s] = !zone.empty();
    const bool still = t.residual && t.residual->norm() < static_px;
    bool moving = false;
    if (!zone.empty()) {
      moving = (std::isfinite(t.epipolar_px) && t.epipolar_px > epipolar_px) || (t.residual && !still);
      for (int z : zone)
        if (t.residual && motion[z] && (*t.residual - *motion[z]).norm() < t.residual->norm()) moving = true;
    } else {
      moving = options.seed_outside_zones && t.residual && !still;
    }
    if (moving)
      ++dynamic_votes[s];
    else if (still)
      ++static_votes[s];
  }
  std::vector<RegionLabel> seeds(n, RegionLabel::kUnlabelled);
  for (int s = 0; s < n; ++s) {
    if (dynamic_votes[s] > static_votes[s] && (in_zone[s] || dynamic_votes[s] >= options.min_outside_votes))
      seeds[s] = RegionLabel::kDynamic;
    else if (static_votes[s] > dynamic_votes[s])
      seeds[s] = RegionLabel::kStatic;
  }
  return seeds;
}

SuperpixelGraph superpixelGraph(const SuperpixelSegmentation& segmentation, const cv::Mat& depth,
                                double depth_edge_ratio) {
  SuperpixelGraph graph;
  // Adjacency from the working-resolution labels when there are any: upsampling adds no new pair of neighbours
  // and loses none.
  const cv::Mat& adjacency_labels = segmentation.working_labels.empty() ? segmentation.labels : segmentation.working_labels;
  graph.neighbours = superpixelNeighbours(adjacency_labels, static_cast<int>(segmentation.superpixels.size()));
  // The full-resolution labels are the working ones upsampled by nearest neighbour: for an integer factor the
  // block scan gives the same edges at a quarter (factor 2) of the pixels.
  const cv::Mat& working = segmentation.working_labels;
  if (const int factor = integerFactor(segmentation.labels.size(), working.size()); factor > 0)
    graph.occlusion_edges = occlusionEdgesOfBlocks(working, factor, graph.neighbours, depth, depth_edge_ratio);
  else
    graph.occlusion_edges = occlusionEdges(segmentation.labels, graph.neighbours, depth, depth_edge_ratio);
  return graph;
}

}  // namespace amos::dynamic
