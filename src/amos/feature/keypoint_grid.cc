#include "amos/feature/keypoint_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"

namespace amos::feature {

KeypointGrid::KeypointGrid(const cv::Rect2d& bounds, const std::vector<cv::KeyPoint>& undistorted_keypoints, int cols,
                           int rows)
    : bounds_(bounds), cols_(cols), rows_(rows) {
  core::require(cols > 0 && rows > 0, fmt::format("KeypointGrid needs a positive grid size, got {}x{}", cols, rows));
  core::require(bounds.width > 0 && bounds.height > 0 && std::isfinite(bounds.x) && std::isfinite(bounds.y),
                "KeypointGrid needs non-empty finite bounds");
  inv_cell_w_ = cols / bounds.width;
  inv_cell_h_ = rows / bounds.height;
  const size_t n = undistorted_keypoints.size();
  std::vector<int> cell_of(n);
  cell_start_.assign(static_cast<size_t>(cols * rows + 1), 0);
  for (size_t i = 0; i < n; ++i) {
    const cv::KeyPoint& kp = undistorted_keypoints[i];
    cell_of[i] = cellRow(kp.pt.y) * cols + cellCol(kp.pt.x);
    ++cell_start_[static_cast<size_t>(cell_of[i] + 1)];
  }
  // Counting sort: prefix sums give each cell's start, then the keypoints are dropped in (ascending index within
  // a cell). Positions and octaves are stored in that cell-major order too, so a window's row of cells is one
  // contiguous run of memory (the searches of tracking and fusion call this hundreds of thousands of times).
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  indices_.resize(n);
  us_.resize(n);
  vs_.resize(n);
  octaves_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const auto slot = static_cast<size_t>(fill[static_cast<size_t>(cell_of[i])]++);
    const cv::KeyPoint& kp = undistorted_keypoints[i];
    indices_[slot] = static_cast<int>(i);
    us_[slot] = kp.pt.x;
    vs_[slot] = kp.pt.y;
    octaves_[slot] = kp.octave;
  }
}

int KeypointGrid::cellCol(double u) const {
  const double c = std::floor((u - bounds_.x) * inv_cell_w_);
  if (!(c >= 0)) return 0;  // also NaN
  return c >= cols_ ? cols_ - 1 : static_cast<int>(c);
}

int KeypointGrid::cellRow(double v) const {
  const double r = std::floor((v - bounds_.y) * inv_cell_h_);
  if (!(r >= 0)) return 0;
  return r >= rows_ ? rows_ - 1 : static_cast<int>(r);
}

std::vector<int> KeypointGrid::featuresInArea(double u, double v, double radius, int min_level, int max_level) const {
  std::vector<int> out;
  featuresInArea(u, v, radius, min_level, max_level, out);
  return out;
}

void KeypointGrid::featuresInArea(double u, double v, double radius, int min_level, int max_level,
                                  std::vector<int>& out) const {
  out.clear();
  if (!(radius > 0) || us_.empty()) return;
  const int c0 = cellCol(u - radius), c1 = cellCol(u + radius);
  const int r0 = cellRow(v - radius), r1 = cellRow(v + radius);
  const bool check_min = min_level >= 0, check_max = max_level >= 0;
  for (int r = r0; r <= r1; ++r) {
    // Cells c0..c1 of a row are adjacent in the cell-major arrays: one run from the first one's start.
    const int begin = cell_start_[static_cast<size_t>(r * cols_ + c0)];
    const int end = cell_start_[static_cast<size_t>(r * cols_ + c1 + 1)];
    for (int k = begin; k < end; ++k) {
      const auto slot = static_cast<size_t>(k);
      const int octave = octaves_[slot];
      if ((check_min && octave < min_level) || (check_max && octave > max_level)) continue;
      if (std::abs(us_[slot] - u) < radius && std::abs(vs_[slot] - v) < radius) out.push_back(indices_[slot]);
    }
  }
}

}  // namespace amos::feature
