#pragma once
// Quality measures for superpixel label maps, used by the tests and the benchmark to choose the superpixel count
// and working scale: boundary recall against reference edges, and the share of pixels that a superpixel
// "leaks" across a reference segmentation.
#include <opencv2/core.hpp>

namespace amos::dynamic {

// CV_8U mask, 255 where a pixel's label differs from its right or lower neighbour (the superpixel borders).
cv::Mat labelBoundaries(const cv::Mat& labels);

// CV_8U mask, 255 where a pixel and its right or lower neighbour both have valid depth (> 0) differing by more
// than min_step_m: the depth discontinuities of a real frame, the edges depth-SLIC should keep.
cv::Mat depthEdges(const cv::Mat& depth, double min_step_m);

// Share of reference edge pixels (255 in reference_edges) that have a boundary pixel of labels within
// tolerance_px (Chebyshev distance). Returns 1 when there is no reference edge.
double boundaryRecall(const cv::Mat& labels, const cv::Mat& reference_edges, int tolerance_px);

// Under-segmentation leak against a reference segmentation (CV_32S): for every superpixel, the pixels outside
// the reference segment it overlaps most, summed and divided by the pixel count. 0 = no superpixel crosses a
// reference border.
double leakage(const cv::Mat& labels, const cv::Mat& reference_labels);

}  // namespace amos::dynamic
