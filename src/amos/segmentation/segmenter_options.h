#pragma once
// Settings of the prior-dynamic-object segmenter (YAML section `Segmentation.`). Plain values with the defaults
// that reproduce the paper's setting as closely as the available models allow; check() names the member at fault
// (core/option_error.h).
#include <string>
#include <vector>

namespace amos::segmentation {

// Structuring element used to grow the masks before they remove keypoints (paper Sec. III-C: "morphological
// expansion of the target mask"; the authors' code uses a 31x31 ellipse).
struct MaskDilationOptions {
  int size = 31;                  // Segmentation.dilationSize: odd side length in pixels; 0 or 1 = no dilation
  std::string shape = "ellipse";  // Segmentation.dilationShape: ellipse | rect | cross
  void check() const;
};

struct SegmenterOptions {
  // Segmentation.backend: name of a backend registered in segmenter_factory.h. Built in (with AMOS_WITH_DNN):
  // "nanodet_selfie" = NanoDet-m boxes + MediaPipe selfie person masks per box.
  std::string backend = "nanodet_selfie";
  // Segmentation.modelsDir: folder with the ONNX files. Empty = found by model_locator.h (--models, settings,
  // $AMOS_MODELS, ./models, ../shared/models); by the time a backend is created this holds the resolved folder.
  std::string models_dir;
  int input_size = 320;             // Segmentation.inputSize: detector input side, 320 or 416
  // Segmentation.inputShape: "square" = input_size x input_size with the frame letterboxed (the shape of the
  // exports), "frame" = the detector input keeps the frame's aspect ratio (longer side input_size, shorter side
  // rounded up to a multiple of 32: 320x256 for 640x480). Same scale either way; "frame" skips the padding rows
  // (detector ~22 -> ~18 ms) and finds the same people (box IoU > 0.95), but with 160 px person crops it sent Bonn
  // crowd into a 55-lost-frame run (ATE 3.6-3.9 cm) in 4 of 11 runs, square in none of 4 (1.65-1.77 cm).
  std::string input_shape = "square";
  // Segmentation.maskInputSize: side of the square the mask network sees each person crop at. The export is 256;
  // the network is fully convolutional, so any multiple of 32 in [64, 256] works, at a cost that grows with the
  // area: 160 costs 8 ms per person instead of 19 ms. Against the authors' YOLACT masks (shared person_masks) 160
  // scores IoU 0.89 / 0.94 where 256 scores 0.89 / 0.96; 128 drops to 0.70 on the two-person frame. On Bonn crowd
  // the 160 and 256 masks agree at IoU 0.92 on average (each misses parts the other finds), and full-mode ATE is
  // the same (1.7-1.8 cm in deterministic runs).
  int mask_input_size = 160;
  float score_threshold = 0.35f;    // Segmentation.scoreThreshold: minimum detector confidence
  float nms_iou = 0.5f;             // Segmentation.nmsIou: per-class non-maximum suppression overlap
  // Segmentation.classes: COCO names to mask. People get a learned mask; other classes a box + depth mask.
  std::vector<std::string> classes = {"person"};
  float box_widen_x = 0.10f;        // Segmentation.boxWidenX: crop widening for the mask net, total fraction of box width
  float box_widen_y = 0.05f;        // Segmentation.boxWidenY: same, of box height
  // Segmentation.carriedBoxWidenX / carriedBoxWidenY: when a person box of an earlier frame is masked again
  // without the detector (Segmenter::resegment, Dynamic.Prior.detectEvery), the box is first grown by these total
  // fractions of its width and height, half on each side, to hold where the person went meanwhile. The box of a
  // person walking across at 1.5 m/s moves ~0.15 m in the 3 frames (100 ms) between two segmentations, a quarter
  // of a walking person's ~0.6 m box width whatever the distance (both scale with 1/depth); a camera turning at
  // 30 deg/s adds ~28 px. 0.5 (a quarter on each side) covers the walk; people barely move vertically: 0.1.
  float carried_box_widen_x = 0.5f;
  float carried_box_widen_y = 0.1f;
  float mask_threshold = 0.5f;      // Segmentation.maskThreshold: person probability above which a pixel is masked
  // Segmentation.borderCropAspect: a person box at the left/right image border whose crop is narrower than this
  // times its height is extended beyond the border (mirrored image) to that width before the mask network sees
  // it; thin squashed crops gave partial or empty masks. 0 = off.
  float border_crop_aspect = 0.45f;
  // Segmentation.minMaskFill: a person whose learned mask covers less than this fraction of its box (the mask
  // network failed, e.g. on motion blur) gets the box + depth mask instead. 0 = off.
  float min_mask_fill = 0.1f;
  // Segmentation.depthTolerance: for non-person classes, pixels of the box whose depth is within this many metres
  // of the object's median depth belong to the object (whole box when there is no usable depth).
  float depth_tolerance = 0.4f;
  int max_instances = 32;           // Segmentation.maxInstances: keep at most this many, highest score first
  MaskDilationOptions dilation;     // Segmentation.dilationSize / dilationShape
  // Segmentation.threads: OpenCV worker threads (cv::setNumThreads, which is process-wide, so it applies to every
  // OpenCV call of the run); 0 = leave OpenCV's setting alone. 1: the segmenter has its own thread and the tracking
  // thread the other core, so OpenCV's extra workers only add contention (with TBB, a thread that finds the
  // thread pool's slots taken waits for them).
  int threads = 1;

  // Throws core::InvalidOption naming the member whose value is invalid.
  void check() const;
};

}  // namespace amos::segmentation
