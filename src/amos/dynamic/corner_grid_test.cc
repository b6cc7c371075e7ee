// Dynamic.Corners.gridCells (issue 16): a low-contrast region gets its share of the corners beside a high-contrast
// one, a flat region gets none made of noise, and the budget is kept.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "amos/dynamic/corner_tracking.h"

namespace amos::dynamic {
namespace {

// Left half: a black/white checkerboard (full contrast); right top quarter: the same pattern at 12 grey levels of
// contrast (a dark fabric); right bottom quarter: flat grey with +-1 grey level of noise.
cv::Mat twoContrasts() {
  cv::Mat img(240, 320, CV_8U, cv::Scalar(120));
  cv::RNG rng(7);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) {
      const bool on = ((x / 12) + (y / 12)) % 2 == 0;
      if (x < 160)
        img.at<uchar>(y, x) = on ? 255 : 0;
      else if (y < 120)
        img.at<uchar>(y, x) = on ? 66 : 54;
      else
        img.at<uchar>(y, x) = static_cast<uchar>(120 + rng.uniform(-1, 2));
    }
  return img;
}

int countIn(const std::vector<cv::Point2f>& corners, const cv::Rect& r) {
  int n = 0;
  for (const cv::Point2f& p : corners) n += r.contains(cv::Point(static_cast<int>(p.x), static_cast<int>(p.y)));
  return n;
}

TEST(CornerGrid, LowContrastRegionGetsItsShareFlatRegionNone) {
  const cv::Mat img = twoContrasts();
  CornerTrackingOptions options;
  options.detection_scale = 1.0;
  options.max_corners = 100;
  // The dim quarter without the column next to the bright half (where the step between the two is a strong edge).
  const cv::Rect dim(165, 0, 155, 125), flat(170, 130, 140, 100);
  const std::vector<cv::Point2f> global = detectCorners(img, options);
  EXPECT_EQ(countIn(global, dim), 0);  // the strongest 100 all lie on the full-contrast half
  options.grid_cells = 4;
  const std::vector<cv::Point2f> grid = detectCorners(img, options);
  EXPECT_GE(countIn(grid, dim), 5);
  EXPECT_EQ(countIn(grid, flat), 0);
  EXPECT_LE(static_cast<int>(grid.size()), options.max_corners);
  EXPECT_GE(static_cast<int>(grid.size()), options.max_corners * 9 / 10);
}

TEST(CornerGrid, RejectsOutOfRangeCells) {
  CornerTrackingOptions options;
  options.grid_cells = 0;
  EXPECT_ANY_THROW(options.check());
  options.grid_cells = 17;
  EXPECT_ANY_THROW(options.check());
}

}  // namespace
}  // namespace amos::dynamic
