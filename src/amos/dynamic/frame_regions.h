#pragma once
// The regions the front end's stages decide on, and what lies at a track's pixel: the prior regions (paper III-A,
// one per connected component of the dilated person mask) and the decision clusters (III-C: the geometric
// clusters without the superpixel blocks at the image border, which take no part in the decisions).
#include <opencv2/core.hpp>
#include <vector>

#include "amos/dynamic/depth_slic.h"

namespace amos::dynamic {

// Connected components (8-connectivity) of a prior mask.
struct PriorRegions {
  cv::Mat components;  // CV_32S: 0 = outside, 1..count = the region of the pixel; empty when there is no prior mask
  int count = 0;
};
// prior_mask: CV_8U, != 0 on prior dynamic objects.
PriorRegions findPriorRegions(const cv::Mat& prior_mask);

struct DecisionRegions {
  std::vector<bool> border;  // per superpixel: a border block (borderSuperpixels)
  cv::Mat decision_map;      // CV_32S cluster of every pixel, -1 in the border blocks (decisionClusterMap)
};
DecisionRegions findDecisionRegions(const SuperpixelSegmentation& segmentation, const cv::Mat& cluster_map,
                                    int border_margin_px);
// The same with the border rule applied per track instead of per block (Dynamic.Boundary.borderBlocks off): no
// superpixel is a border block, and only the pixels within edge_margin_px of the image edge are -1 in the decision
// map, so a track whose current pixel lies there takes no part in the decisions (nor seeds the mask).
DecisionRegions findEdgeDecisionRegions(const SuperpixelSegmentation& segmentation, const cv::Mat& cluster_map,
                                        int edge_margin_px);

// The value of a CV_32S label map at the pixel nearest p; -1 outside the image (or for an empty map).
int labelAt(const cv::Mat& map, cv::Point2f p);

// Whether the pixel nearest p is set in a CV_8U mask (false outside the image or for an empty mask).
bool maskAt(const cv::Mat& mask, cv::Point2f p);

}  // namespace amos::dynamic
