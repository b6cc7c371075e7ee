#pragma once
// OpenCV-dnn segmentation backends (compiled only with AMOS_WITH_DNN; implemented in segmenter_dnn.cc).
//
// "nanodet_selfie": NanoDet-m (COCO detector, the 320 or 416 export, on its square input or a frame-shaped one such
// as 320x256, see nanodet_import_dnn.h) finds boxes of the configured classes; for each person box a MediaPipe
// selfie-segmentation network gives the mask: the box is widened (box_widen_x/y), the crop squashed to
// mask_input_size x mask_input_size (160 by default; the export's 256 costs 2.4 times as much), the person
// probability thresholded and pasted back inside the box. Other classes get a box + depth mask
// (segment_depth_mask.h). This replaces the paper's YOLACT, whose weights are not available here; see
// /work/shared/models/README.md for the models and why they are chained this way.
#include <memory>
#include <string>
#include <vector>

#include "amos/segmentation/segmenter.h"
#include "amos/segmentation/segmenter_options.h"

namespace amos::segmentation {

class SegmenterFactory;

// File names the nanodet_selfie backend needs for these options (nanodet_m_<input_size>.onnx, selfie_seg_256.onnx).
std::vector<std::string> nanodetSelfieModelFiles(const SegmenterOptions& options);

// Loads both networks from options.models_dir and runs each once on a blank image, so a missing, corrupt or
// incompatible model throws core::Error (naming the file) here rather than at the first frame.
std::unique_ptr<Segmenter> makeNanoDetSelfieSegmenter(const SegmenterOptions& options);

// Registers "nanodet_selfie".
void addDnnSegmenterBackends(SegmenterFactory& factory);

}  // namespace amos::segmentation
