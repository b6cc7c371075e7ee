#pragma once
// Decoding of NanoDet (GFL head) outputs into boxes, without any dnn dependency so it can be tested on
// hand-made tensors. NanoDet-m has three heads (strides 8, 16, 32); each gives per cell a score for each of the
// 80 classes (sigmoid already applied) and, for each of the 4 box sides (left, top, right, bottom), a discrete
// distribution over reg_max + 1 distance bins (General Focal Loss): the side distance is the softmax-weighted
// mean bin times the stride.
#include <opencv2/core.hpp>

#include <vector>

namespace amos::segmentation {

// One head: scores is N x num_classes, distributions is N x 4*(reg_max+1), both CV_32F; row r is cell
// (i, j) = (r / cols, r % cols) of the (input/stride) x (input/stride) grid.
struct NanoDetHead {
  int stride = 0;
  int cols = 0;  // grid columns (input width / stride); 0 = square grid, taken from the number of rows
  cv::Mat scores;
  cv::Mat distributions;
};

struct Detection {
  int class_id = -1;
  float score = 0.f;
  cv::Rect2f box;  // x, y, width, height (in network input pixels after decoding, image pixels after unletterbox)
};

// Sorts raw network outputs into heads by shape, not by name: each output has shape [1, N, C] (or [N, C]);
// C == reg_bins*4 marks a box map, any other C a score map; N = (width / stride) * (height / stride) of the network
// input gives the stride. Throws core::Error when the outputs do not form complete heads for the strides {8, 16, 32}.
std::vector<NanoDetHead> nanodetHeadsFromOutputs(const std::vector<cv::Mat>& outputs, cv::Size input_size,
                                                 int reg_max = 7);
// Square input of side input_size.
std::vector<NanoDetHead> nanodetHeadsFromOutputs(const std::vector<cv::Mat>& outputs, int input_size,
                                                 int reg_max = 7);

// Candidate boxes in network input pixels: for every cell, the best score over `class_ids` (all classes when
// empty); cells at or above score_threshold give one detection of that class. Cell centre is
// ((j + 0.5) * s - 0.5, (i + 0.5) * s - 0.5).
std::vector<Detection> decodeNanoDet(const std::vector<NanoDetHead>& heads, const std::vector<int>& class_ids,
                                     float score_threshold, int reg_max = 7);

// Expected value of a discrete distribution given by logits (softmax then sum_k k * p_k). Exposed for tests.
float distributionIntegral(const float* logits, int bins);

// Greedy non-maximum suppression within each class: highest score first, drop boxes overlapping a kept box of
// the same class with IoU > iou_threshold. Result sorted by descending score.
std::vector<Detection> nmsPerClass(std::vector<Detection> detections, float iou_threshold);

float boxIoU(const cv::Rect2f& a, const cv::Rect2f& b);

// Network input for an image: `square` gives side x side (the shape the NanoDet exports were made for);
// otherwise the image's aspect ratio is kept: the longer side is `side`, the other one the image's scaled side
// rounded up to a multiple of 32 (the coarsest stride), e.g. 640x480 at 320 -> 320x256. A 4:3 frame letterboxed
// into a square wastes a quarter of the detector's work on padding; this shape wastes 6%.
cv::Size detectorInputSize(cv::Size image_size, int side, bool square);

// Aspect-preserving resize into the network input, centred, padded with zeros.
struct Letterbox {
  float scale = 1.f;           // input pixels per image pixel
  float pad_x = 0, pad_y = 0;  // offset of the resized image inside the input
  cv::Size input;              // network input size
};
Letterbox makeLetterbox(cv::Size image_size, cv::Size input_size);
Letterbox makeLetterbox(cv::Size image_size, int input_size);  // square input
cv::Mat applyLetterbox(const cv::Mat& bgr, const Letterbox& letterbox);
// Maps a box from input pixels back to image pixels, clipped to the image.
cv::Rect2f unletterboxBox(const cv::Rect2f& box, const Letterbox& letterbox, cv::Size image_size);

}  // namespace amos::segmentation
