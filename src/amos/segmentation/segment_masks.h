#pragma once
// Mask operations around the segmenter: painting per-box instance masks into a frame, growing them by the
// configured structuring element (paper Sec. III-C) and comparing masks.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "amos/segmentation/segmenter.h"
#include "amos/segmentation/segmenter_options.h"

namespace amos::segmentation {

// Union of the instances' masks in a frame of `size`: CV_8UC1, 255 where any instance is, 0 elsewhere.
cv::Mat paintInstances(const std::vector<SegmentedInstance>& instances, cv::Size size);

// Structuring element of the options (empty Mat when dilation is off).
cv::Mat dilationKernel(const MaskDilationOptions& options);

// mask grown by the structuring element; only the neighbourhood of the non-zero pixels is processed, so an
// empty or small mask costs little. Pixels beyond the image border count as 0.
cv::Mat dilateMask(const cv::Mat& mask, const MaskDilationOptions& options);

// Intersection over union of two binary masks (non-zero = set). Two empty masks give 1.
double maskIoU(const cv::Mat& a, const cv::Mat& b);

// Pastes a probability map computed on `crop` (any size, CV_32F in [0, 1]) back into the image: the map is
// resized to the crop, thresholded (> threshold) and the part inside `box` is returned as a box-sized CV_8UC1
// 0/255 mask. crop must contain box.
cv::Mat pasteProbabilityMask(const cv::Mat& probability, const cv::Rect& crop, const cv::Rect& box, float threshold);

// box grown by widen_x * width and widen_y * height in total (half on each side), clipped to the image.
cv::Rect widenBox(const cv::Rect& box, float widen_x, float widen_y, cv::Size image_size);

// A person cut by the left or right image border gives a thin crop, which the mask network (trained on whole
// upper bodies) segments badly once it is squashed to its square input. When `box` touches that border and `crop`
// is narrower than min_aspect * height, the crop is extended beyond the border to that width; the part outside
// the image is then filled by mirroring (imagePatch). min_aspect <= 0 leaves the crop alone.
cv::Rect extendBorderCrop(const cv::Rect& box, const cv::Rect& crop, cv::Size image_size, float min_aspect);

// The pixels of `rect`, which may reach outside the image; outside pixels mirror the image (BORDER_REFLECT).
cv::Mat imagePatch(const cv::Mat& image, const cv::Rect& rect);

// Colour overlay for inspection: instances tinted per instance, outlines, boxes and "class score" labels.
cv::Mat drawOverlay(const cv::Mat& bgr, const std::vector<SegmentedInstance>& instances);

// Tiles images (CV_8UC3, any sizes) into one sheet, `columns` wide, each scaled to tile_width keeping its
// aspect ratio, with the caption of the same index (if any) written in its corner.
cv::Mat contactSheet(const std::vector<cv::Mat>& images, const std::vector<std::string>& captions, int columns,
                     int tile_width);

}  // namespace amos::segmentation
