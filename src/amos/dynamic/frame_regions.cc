#include "amos/dynamic/frame_regions.h"

#include <algorithm>
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

DecisionRegions findEdgeDecisionRegions(const SuperpixelSegmentation& segmentation, const cv::Mat& cluster_map,
                                        int edge_margin_px) {
  DecisionRegions regions;
  regions.border.assign(segmentation.superpixels.size(), false);
  regions.decision_map = cluster_map.clone();
  const int w = cluster_map.cols, h = cluster_map.rows;
  const int m = std::min(std::max(0, edge_margin_px), std::min(w, h) / 2);
  if (m > 0) {
    regions.decision_map.rowRange(0, m).setTo(-1);
    regions.decision_map.rowRange(h - m, h).setTo(-1);
    regions.decision_map.colRange(0, m).setTo(-1);
    regions.decision_map.colRange(w - m, w).setTo(-1);
  }
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
