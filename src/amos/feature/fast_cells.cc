#include "amos/feature/fast_cells.h"

#include <opencv2/features2d.hpp>

#include <algorithm>

namespace amos::feature {

namespace {
constexpr int kFastRadius = 3;

// FAST on the level rectangle `cell` (level coordinates), reading kFastRadius pixels of context around it so that
// corners can be found up to the rectangle's edge. Appends corners in level coordinates.
void fastInRect(const cv::Mat& padded, int border, const cv::Rect& cell, int threshold, const cv::Mat& mask,
                const cv::Rect& allowed, std::vector<cv::KeyPoint>& out) {
  const cv::Rect region(border + cell.x - kFastRadius, border + cell.y - kFastRadius, cell.width + 2 * kFastRadius,
                        cell.height + 2 * kFastRadius);
  std::vector<cv::KeyPoint> found;
  cv::FAST(padded(region), found, threshold, true);
  for (cv::KeyPoint& kp : found) {
    kp.pt.x += static_cast<float>(cell.x - kFastRadius);
    kp.pt.y += static_cast<float>(cell.y - kFastRadius);
    if (!allowed.contains(cv::Point(static_cast<int>(kp.pt.x), static_cast<int>(kp.pt.y)))) continue;
    if (!mask.empty() && mask.at<std::uint8_t>(static_cast<int>(kp.pt.y), static_cast<int>(kp.pt.x)) == 0) continue;
    out.push_back(kp);
  }
}
}  // namespace

std::vector<cv::KeyPoint> detectFastInCells(const cv::Mat& padded, int border, cv::Size size,
                                            const FastCellOptions& options, const cv::Mat& mask) {
  std::vector<cv::KeyPoint> corners;
  if (size.width <= 0 || size.height <= 0) return corners;
  const int m = options.edge_margin;
  const cv::Rect allowed(m, m, size.width - 2 * m, size.height - 2 * m);
  if (allowed.width <= 0 || allowed.height <= 0) return corners;
  fastInRect(padded, border, cv::Rect(0, 0, size.width, size.height), options.ini_threshold, mask, allowed, corners);
  if (options.min_threshold >= options.ini_threshold) return corners;

  // Cells of about cell_size pixels tiling the level exactly; cell c spans [edge(c), edge(c + 1)).
  const int cols = std::max(1, (size.width + options.cell_size / 2) / options.cell_size);
  const int rows = std::max(1, (size.height + options.cell_size / 2) / options.cell_size);
  auto edges = [](int length, int cells) {
    std::vector<int> e(static_cast<size_t>(cells + 1));
    for (int c = 0; c <= cells; ++c) e[static_cast<size_t>(c)] = c * length / cells;
    return e;
  };
  const std::vector<int> xs = edges(size.width, cols), ys = edges(size.height, rows);
  auto cellOf = [](const std::vector<int>& e, int v) {
    return static_cast<int>(std::upper_bound(e.begin() + 1, e.end() - 1, v) - (e.begin() + 1));
  };
  std::vector<char> has_corner(static_cast<size_t>(cols * rows), 0);
  for (const cv::KeyPoint& kp : corners) {
    const int c = cellOf(xs, static_cast<int>(kp.pt.x)), r = cellOf(ys, static_cast<int>(kp.pt.y));
    has_corner[static_cast<size_t>(r * cols + c)] = 1;
  }
  // A cell the mask forbids entirely cannot gain a corner from the lower threshold: no second FAST pass there
  // (with a mask over the people in view, that is much of the image).
  if (!mask.empty()) {
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        const cv::Rect cell(xs[c], ys[r], xs[c + 1] - xs[c], ys[r + 1] - ys[r]);
        if (cv::countNonZero(mask(cell)) == 0) has_corner[static_cast<size_t>(r * cols + c)] = 1;
      }
    }
  }
  // Horizontal runs of empty cells are searched in one FAST call each: cv::FAST has a per-call cost that would
  // otherwise dominate when many small cells fall back.
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols;) {
      if (has_corner[static_cast<size_t>(r * cols + c)]) {
        ++c;
        continue;
      }
      int end = c + 1;
      while (end < cols && !has_corner[static_cast<size_t>(r * cols + end)]) ++end;
      const cv::Rect run(xs[c], ys[r], xs[end] - xs[c], ys[r + 1] - ys[r]);
      fastInRect(padded, border, run, options.min_threshold, mask, allowed, corners);
      c = end;
    }
  }
  return corners;
}

}  // namespace amos::feature
