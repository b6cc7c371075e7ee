#pragma once
// FAST corners of one pyramid level, searched cell by cell so that weakly textured regions still contribute:
// a cell where no corner reaches the initial threshold is searched again with the lower one (ORB-SLAM2's
// iniThFAST / minThFAST scheme).
#include <opencv2/core.hpp>

#include <vector>

namespace amos::feature {

struct FastCellOptions {
  int ini_threshold = 20;
  int min_threshold = 7;
  int cell_size = 30;  // pixels (ORB-SLAM2 uses 30)
  // Corners closer than this to the level's edge are dropped. There the FAST circle (radius 3) and the non-maximum
  // suppression read the reflected border, and the mirror axis itself makes corners: they stay pinned to the image
  // edge while the scene moves, i.e. systematically wrong measurements of the motion.
  int edge_margin = 4;
};

// padded: a level image with `border` >= 3 reflected pixels on each side; size: the level size without border.
// mask (optional, same size as the level, 0 = forbidden): corners on forbidden pixels (and within edge_margin of the
// level's edge) are dropped before the cell's fallback decision. Returns corners in level coordinates, with response = FAST score; deterministic order.
std::vector<cv::KeyPoint> detectFastInCells(const cv::Mat& padded, int border, cv::Size size,
                                            const FastCellOptions& options, const cv::Mat& mask = cv::Mat());

}  // namespace amos::feature
