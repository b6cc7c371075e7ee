#include "amos/dynamic/boundary_assignment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"

namespace amos::dynamic {

void BoundaryOptions::check() const {
  core::require(search_radius_px >= 0, fmt::format("Dynamic.Boundary.radius must be >= 0, got {}", search_radius_px));
  core::require(border_margin_px >= 0,
                fmt::format("Dynamic.Boundary.borderMargin must be >= 0, got {}", border_margin_px));
}

std::vector<bool> borderSuperpixels(const cv::Mat& superpixel_labels, int count, int margin_px) {
  core::require(superpixel_labels.type() == CV_32S, "borderSuperpixels: labels must be CV_32S");
  core::require(margin_px >= 0, "borderSuperpixels: margin must be >= 0");
  std::vector<bool> border(std::max(0, count), false);
  const int w = superpixel_labels.cols, h = superpixel_labels.rows;
  const int m = std::min(margin_px, std::max(0, std::min(w, h) / 2 - 1));
  auto mark = [&](int x, int y) {
    const int label = superpixel_labels.at<int>(y, x);
    core::require(label >= 0 && label < count, "borderSuperpixels: label out of range");
    border[label] = true;
  };
  for (int y = 0; y < h; ++y) {
    const bool edge_row = y <= m || y >= h - 1 - m;
    for (int x = 0; x < w; ++x) {
      if (edge_row || x <= m || x >= w - 1 - m) mark(x, y);
    }
  }
  return border;
}

cv::Mat decisionClusterMap(const cv::Mat& cluster_map, const cv::Mat& superpixel_labels,
                           const std::vector<bool>& border_superpixels) {
  core::require(cluster_map.type() == CV_32S && superpixel_labels.type() == CV_32S &&
                    cluster_map.size() == superpixel_labels.size(),
                "decisionClusterMap: both maps must be CV_32S of the same size");
  cv::Mat out = cluster_map.clone();
  for (int y = 0; y < out.rows; ++y) {
    const int* sp = superpixel_labels.ptr<int>(y);
    int* o = out.ptr<int>(y);
    for (int x = 0; x < out.cols; ++x)
      if (border_superpixels.at(sp[x])) o[x] = -1;
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

}  // namespace amos::dynamic
