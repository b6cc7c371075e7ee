#include "amos/dynamic/frame_regions.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "amos/dynamic/boundary_assignment.h"

namespace amos::dynamic {

PriorRegions findPriorRegions(const cv::Mat& prior_mask) {
  PriorRegions regions;
  regions.count = cv::connectedComponents(prior_mask != 0, regions.components, 8, CV_32S) - 1;
  return regions;
}

DecisionRegions findDecisionRegions(const SuperpixelSegmentation& segmentation, const cv::Mat& cluster_map,
                                    int border_margin_px) {
  DecisionRegions regions;
  regions.border = borderSuperpixels(segmentation.labels, static_cast<int>(segmentation.superpixels.size()),
                                     border_margin_px);
  regions.decision_map = decisionClusterMap(cluster_map, segmentation.labels, regions.border);
  return regions;
}

int labelAt(const cv::Mat& map, cv::Point2f p) {
  const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
  if (x < 0 || y < 0 || x >= map.cols || y >= map.rows) return -1;
  return map.at<int>(y, x);
}

bool maskAt(const cv::Mat& mask, cv::Point2f p) {
  const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
  return x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<uchar>(y, x) != 0;
}

}  // namespace amos::dynamic
