#pragma once
// Spatial index over a frame's undistorted keypoints for window searches (projection matching, stereo-free
// RGB-D tracking): a grid of cells over the undistorted image bounds, 64 x 48 as in ORB-SLAM2.
#include <opencv2/core.hpp>

#include <vector>

namespace amos::feature {

class KeypointGrid {
 public:
  static constexpr int kDefaultCols = 64;
  static constexpr int kDefaultRows = 48;

  KeypointGrid() = default;
  // bounds: where undistorted keypoints can fall (core::PinholeCamera::undistortedBounds()). Keypoints outside
  // the bounds are filed in the nearest border cell, so no keypoint is ever unreachable.
  KeypointGrid(const cv::Rect2d& bounds, const std::vector<cv::KeyPoint>& undistorted_keypoints,
               int cols = kDefaultCols, int rows = kDefaultRows);

  // Indices of the keypoints with |u_i - u| < radius and |v_i - v| < radius (a square window, as ORB-SLAM2),
  // whose octave is >= min_level and <= max_level; a negative bound means "no bound". Cell-major order
  // (deterministic); empty when radius <= 0.
  std::vector<int> featuresInArea(double u, double v, double radius, int min_level = -1, int max_level = -1) const;
  // Same, appending to `out` after clearing it (no allocation once `out` has grown).
  void featuresInArea(double u, double v, double radius, int min_level, int max_level, std::vector<int>& out) const;

  int cols() const { return cols_; }
  int rows() const { return rows_; }
  size_t size() const { return us_.size(); }
  // Cell column / row of a position (clamped to the grid).
  int cellCol(double u) const;
  int cellRow(double v) const;

 private:
  cv::Rect2d bounds_;
  int cols_ = 0, rows_ = 0;
  double inv_cell_w_ = 0, inv_cell_h_ = 0;
  // Cell-major arrays: cell c holds slots [cell_start_[c], cell_start_[c + 1]); slot k is keypoint indices_[k],
  // at (us_[k], vs_[k]) of octave octaves_[k].
  std::vector<int> cell_start_;
  std::vector<int> indices_;
  std::vector<float> us_, vs_;
  std::vector<int> octaves_;
};

}  // namespace amos::feature
