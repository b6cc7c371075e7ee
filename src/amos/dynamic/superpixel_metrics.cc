#include "amos/dynamic/superpixel_metrics.h"

#include <map>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "amos/core/error.h"

namespace amos::dynamic {

cv::Mat labelBoundaries(const cv::Mat& labels) {
  core::require(labels.type() == CV_32S, "labelBoundaries: labels must be CV_32S");
  cv::Mat out(labels.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < labels.rows; ++y) {
    const int* row = labels.ptr<int>(y);
    const int* below = y + 1 < labels.rows ? labels.ptr<int>(y + 1) : nullptr;
    uchar* o = out.ptr<uchar>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if ((x + 1 < labels.cols && row[x + 1] != row[x]) || (below && below[x] != row[x])) o[x] = 255;
    }
  }
  return out;
}

cv::Mat depthEdges(const cv::Mat& depth, double min_step_m) {
  core::require(depth.type() == CV_32F, "depthEdges: depth must be CV_32F");
  cv::Mat out(depth.size(), CV_8U, cv::Scalar(0));
  const float step = static_cast<float>(min_step_m);
  auto valid = [](float z) { return z > 0.f && z < 1e6f; };
  for (int y = 0; y < depth.rows; ++y) {
    const float* row = depth.ptr<float>(y);
    const float* below = y + 1 < depth.rows ? depth.ptr<float>(y + 1) : nullptr;
    uchar* o = out.ptr<uchar>(y);
    for (int x = 0; x < depth.cols; ++x) {
      if (!valid(row[x])) continue;
      if (x + 1 < depth.cols && valid(row[x + 1]) && std::abs(row[x + 1] - row[x]) > step) o[x] = 255;
      if (below && valid(below[x]) && std::abs(below[x] - row[x]) > step) o[x] = 255;
    }
  }
  return out;
}

double boundaryRecall(const cv::Mat& labels, const cv::Mat& reference_edges, int tolerance_px) {
  core::require(reference_edges.type() == CV_8U && reference_edges.size() == labels.size(),
                "boundaryRecall: reference_edges must be CV_8U with the size of labels");
  core::require(tolerance_px >= 0, "boundaryRecall: tolerance must be >= 0");
  cv::Mat near = labelBoundaries(labels);
  if (tolerance_px > 0) {
    const cv::Mat kernel = cv::Mat::ones(2 * tolerance_px + 1, 2 * tolerance_px + 1, CV_8U);
    cv::dilate(near, near, kernel);
  }
  const int total = cv::countNonZero(reference_edges);
  if (total == 0) return 1.0;
  cv::Mat hit;
  cv::bitwise_and(near, reference_edges, hit);
  return static_cast<double>(cv::countNonZero(hit)) / total;
}

double leakage(const cv::Mat& labels, const cv::Mat& reference_labels) {
  core::require(
      labels.type() == CV_32S && reference_labels.type() == CV_32S && labels.size() == reference_labels.size(),
      "leakage: both label maps must be CV_32S of the same size");
  std::map<int, std::map<int, long>> overlap;  // superpixel -> reference segment -> pixel count
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) ++overlap[labels.at<int>(y, x)][reference_labels.at<int>(y, x)];
  long leaked = 0;
  for (const auto& [label, segments] : overlap) {
    long total = 0, best = 0;
    for (const auto& [segment, count] : segments) total += count, best = std::max(best, count);
    leaked += total - best;
  }
  return static_cast<double>(leaked) / labels.total();
}

}  // namespace amos::dynamic
