#include "amos/dynamic/corner_tracking.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::dynamic {

void CornerTrackingOptions::check() const {
  core::requireAtLeast(max_corners, "max_corners", 8);
  core::requireOption(quality_level > 0 && quality_level < 1, core::option(quality_level, "quality_level"),
                      fmt::format("must lie in (0, 1), got {}", quality_level));
  core::requireAtLeast(min_distance_px, "min_distance_px", 0);
  core::requireOption(detection_scale > 0 && detection_scale <= 1, core::option(detection_scale, "detection_scale"),
                      fmt::format("must lie in (0, 1], got {}", detection_scale));
  core::requireOption(lk_window >= 5 && lk_window % 2 == 1, core::option(lk_window, "lk_window"),
                      fmt::format("must be an odd number >= 5, got {}", lk_window));
  core::requireOption(lk_levels >= 0 && lk_levels <= 6, core::option(lk_levels, "lk_levels"),
                      fmt::format("must lie in [0, 6], got {}", lk_levels));
  core::requireAtLeast(lk_max_iterations, "lk_max_iterations", 1);
  core::requirePositive(lk_epsilon, "lk_epsilon");
  core::requirePositive(forward_backward_px, "forward_backward_px");
  core::requireOption(grid_cells >= 1 && grid_cells <= 16, core::option(grid_cells, "grid_cells"),
                      fmt::format("must lie in [1, 16], got {}", grid_cells));
}

ImagePyramid buildPyramid(const cv::Mat& gray, const CornerTrackingOptions& options) {
  options.check();
  core::require(!gray.empty() && gray.type() == CV_8UC1, "buildPyramid: the image must be a non-empty CV_8UC1");
  ImagePyramid pyramid;
  cv::buildOpticalFlowPyramid(gray, pyramid, cv::Size(options.lk_window, options.lk_window), options.lk_levels);
  return pyramid;
}

FramePairPyramids buildPyramids(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                const CornerTrackingOptions& options) {
  core::require(!last_gray.empty() && last_gray.type() == CV_8UC1 && current_gray.type() == CV_8UC1 &&
                    last_gray.size() == current_gray.size(),
                "buildPyramids: both images must be CV_8UC1 of the same size");
  return {buildPyramid(last_gray, options), buildPyramid(current_gray, options)};
}

std::vector<PointTrack> trackPoints(const FramePairPyramids& pyramids, const std::vector<cv::Point2f>& points,
                                    const CornerTrackingOptions& options) {
  options.check();
  core::require(!pyramids.last.empty() && !pyramids.current.empty(), "trackPoints: pyramids are empty");
  std::vector<PointTrack> tracks;
  if (points.empty()) return tracks;
  const cv::Size window(options.lk_window, options.lk_window);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, options.lk_max_iterations,
                              options.lk_epsilon);
  std::vector<cv::Point2f> forward;
  std::vector<uchar> ok_forward;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(pyramids.last, pyramids.current, points, forward, ok_forward, error, window,
                           options.lk_levels, stop);
  // Only the points that converged inside the image go back (LK treats every point on its own, so leaving the
  // others out changes nothing for these). The backward pass starts where the forward pass ended, without a hint
  // towards the original point, so that only a track consistent in both directions returns to it.
  const cv::Size size = pyramids.current.front().size();
  const cv::Rect2f inside(0.f, 0.f, static_cast<float>(size.width - 1), static_cast<float>(size.height - 1));
  std::vector<int> candidates;
  std::vector<cv::Point2f> returning;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!ok_forward[i] || !inside.contains(forward[i])) continue;
    candidates.push_back(static_cast<int>(i));
    returning.push_back(forward[i]);
  }
  if (candidates.empty()) return tracks;
  if (!options.forward_backward_check) {
    for (int i : candidates)
      tracks.push_back({points[static_cast<std::size_t>(i)], forward[static_cast<std::size_t>(i)], i});
    return tracks;
  }
  std::vector<cv::Point2f> backward;
  std::vector<uchar> ok_backward;
  cv::calcOpticalFlowPyrLK(pyramids.current, pyramids.last, returning, backward, ok_backward, error, window,
                           options.lk_levels, stop);
  const float fb2 = static_cast<float>(options.forward_backward_px * options.forward_backward_px);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (!ok_backward[k]) continue;
    const int i = candidates[k];
    const cv::Point2f d = backward[k] - points[static_cast<std::size_t>(i)];
    if (d.dot(d) > fb2) continue;
    tracks.push_back({points[static_cast<std::size_t>(i)], forward[static_cast<std::size_t>(i)], i});
  }
  return tracks;
}

std::vector<PointTrack> trackCorners(const cv::Mat& last_gray, const cv::Mat& current_gray,
                                     const CornerTrackingOptions& options, const cv::Mat& mask) {
  return trackCorners(last_gray, buildPyramids(last_gray, current_gray, options), options, mask);
}

std::vector<PointTrack> trackCorners(const cv::Mat& last_gray, const FramePairPyramids& pyramids,
                                     const CornerTrackingOptions& options, const cv::Mat& mask) {
  core::require(!last_gray.empty() && !pyramids.last.empty() && pyramids.last.front().size() == last_gray.size(),
                "trackCorners: the last frame's pyramid does not belong to its image");
  return trackPoints(pyramids, detectCorners(last_gray, options, mask), options);
}

namespace {

// Shi-Tomasi corners with CornerTrackingOptions::grid_cells > 1, selected from one eigenvalue image: each cell's
// share first (ranked against that cell's best), then the image's strongest. The same rules as goodFeaturesToTrack
// (3x3 block, local maxima of the minimum eigenvalue, quality relative to the best, greedy minimum distance,
// strongest first), so the cost is one goodFeaturesToTrack call, not one per cell.
std::vector<cv::Point2f> gridCorners(const cv::Mat& image, const cv::Mat& mask, const CornerTrackingOptions& options,
                                     double min_distance) {
  constexpr double kCellFloor = 1e-3;  // a cell's best corner against the image's best (see grid_cells)
  const int g = options.grid_cells;
  cv::Mat eig, dilated;
  cv::cornerMinEigenVal(image, eig, 3, 3);
  cv::dilate(eig, dilated, cv::Mat());
  // Local maxima (as goodFeaturesToTrack: 3x3, one pixel in from the image edge), with their cell.
  struct Candidate {
    float response;
    int x, y, cell;
  };
  std::vector<Candidate> candidates;
  std::vector<float> cell_best(static_cast<std::size_t>(g * g), 0.f);
  float image_best = 0.f;
  for (int y = 1; y < image.rows - 1; ++y) {
    const float* e = eig.ptr<float>(y);
    const float* d = dilated.ptr<float>(y);
    const uchar* m = mask.empty() ? nullptr : mask.ptr<uchar>(y);
    const int cy = y * g / image.rows;
    for (int x = 1; x < image.cols - 1; ++x) {
      if (!(e[x] > 0.f) || e[x] != d[x] || (m && !m[x])) continue;
      const int cell = cy * g + x * g / image.cols;
      candidates.push_back({e[x], x, y, cell});
      cell_best[static_cast<std::size_t>(cell)] = std::max(cell_best[static_cast<std::size_t>(cell)], e[x]);
      image_best = std::max(image_best, e[x]);
    }
  }
  // Strongest first; ties in raster order, so the selection is deterministic.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.response > b.response; });
  // Minimum distance: accepted corners bucketed in cells of min_distance, so each test looks at 3 x 3 buckets.
  const double r = std::max(1.0, min_distance);
  const int bw = static_cast<int>(std::ceil(image.cols / r)) + 1, bh = static_cast<int>(std::ceil(image.rows / r)) + 1;
  std::vector<std::vector<cv::Point2f>> buckets(static_cast<std::size_t>(bw * bh));
  std::vector<cv::Point2f> corners;
  std::vector<float> responses;
  auto tryAccept = [&](const Candidate& c) {
    const int bx = static_cast<int>(c.x / r), by = static_cast<int>(c.y / r);
    if (min_distance > 0)
      for (int y = std::max(0, by - 1); y <= std::min(bh - 1, by + 1); ++y)
        for (int x = std::max(0, bx - 1); x <= std::min(bw - 1, bx + 1); ++x)
          for (const cv::Point2f& p : buckets[static_cast<std::size_t>(y * bw + x)]) {
            const double dx = p.x - c.x, dy = p.y - c.y;
            if (dx * dx + dy * dy < min_distance * min_distance) return false;
          }
    const cv::Point2f p(static_cast<float>(c.x), static_cast<float>(c.y));
    buckets[static_cast<std::size_t>(by * bw + bx)].push_back(p);
    corners.push_back(p);
    responses.push_back(c.response);
    return true;
  };
  // Each cell's share, against the cell's own best; a cell whose best is below the floor (flat) gets none.
  const int per_cell = std::max(1, options.max_corners / (2 * g * g));
  std::vector<int> taken(static_cast<std::size_t>(g * g), 0);
  std::vector<bool> used(candidates.size(), false);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& c = candidates[i];
    const auto cell = static_cast<std::size_t>(c.cell);
    if (taken[cell] >= per_cell || !(cell_best[cell] > kCellFloor * image_best) ||
        c.response < options.quality_level * cell_best[cell])
      continue;
    if (tryAccept(c)) {
      ++taken[cell];
      used[i] = true;
    }
  }
  // The rest of the budget: the image's strongest corners, away from those already taken.
  for (std::size_t i = 0; i < candidates.size() && static_cast<int>(corners.size()) < options.max_corners; ++i) {
    if (used[i] || candidates[i].response < options.quality_level * image_best) continue;
    tryAccept(candidates[i]);
  }
  // Strongest first, as goodFeaturesToTrack returns them.
  std::vector<std::size_t> order(corners.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return responses[a] > responses[b]; });
  std::vector<cv::Point2f> sorted;
  sorted.reserve(order.size());
  for (std::size_t i : order) sorted.push_back(corners[i]);
  return sorted;
}

void goodCorners(const cv::Mat& image, std::vector<cv::Point2f>& corners, const CornerTrackingOptions& options,
                 double min_distance, const cv::Mat& mask) {
  if (options.grid_cells > 1)
    corners = gridCorners(image, mask, options, min_distance);
  else
    cv::goodFeaturesToTrack(image, corners, options.max_corners, options.quality_level, min_distance, mask);
}

}  // namespace

std::vector<cv::Point2f> detectCorners(const cv::Mat& gray, const CornerTrackingOptions& options, const cv::Mat& mask) {
  options.check();
  core::require(!gray.empty() && gray.type() == CV_8UC1, "detectCorners: the image must be a non-empty CV_8UC1");
  core::require(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == gray.size()),
                "detectCorners: the mask must be empty or CV_8UC1 of the image size");
  std::vector<cv::Point2f> corners;
  if (options.detection_scale < 1.0) {
    const double s = options.detection_scale;
    cv::Mat small, small_mask;
    cv::resize(gray, small, cv::Size(), s, s, cv::INTER_AREA);
    if (!mask.empty()) cv::resize(mask, small_mask, small.size(), 0, 0, cv::INTER_NEAREST);
    goodCorners(small, corners, options, options.min_distance_px * s, small_mask);
    // Pixel centres: small (x + 0.5) / s - 0.5 in the full image.
    for (cv::Point2f& c : corners)
      c = cv::Point2f(static_cast<float>((c.x + 0.5) / s - 0.5), static_cast<float>((c.y + 0.5) / s - 0.5));
  } else {
    goodCorners(gray, corners, options, options.min_distance_px, mask);
  }
  return corners;
}

}  // namespace amos::dynamic
