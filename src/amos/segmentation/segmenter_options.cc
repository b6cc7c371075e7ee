#include "amos/segmentation/segmenter_options.h"

#include <fmt/format.h>

#include <algorithm>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/segmentation/segmenter_classes.h"

namespace amos::segmentation {

void MaskDilationOptions::check() const {
  core::requireOption(size >= 0 && size <= 255 && (size <= 1 || size % 2 == 1), core::option(size, "size"),
                      fmt::format("must be 0, 1 or an odd number up to 255, got {}", size));
  core::requireOption(shape == "ellipse" || shape == "rect" || shape == "cross", core::option(shape, "shape"),
                      fmt::format("must be ellipse, rect or cross, got '{}'", shape));
}

void SegmenterOptions::check() const {
  core::requireOption(!backend.empty(), core::option(backend, "backend"), "must not be empty");
  core::requireOption(input_size == 320 || input_size == 416, core::option(input_size, "input_size"),
                      fmt::format("must be 320 or 416 (the available NanoDet exports), got {}", input_size));
  core::requireOption(input_shape == "frame" || input_shape == "square", core::option(input_shape, "input_shape"),
                      fmt::format("must be frame or square, got '{}'", input_shape));
  core::requireOption(mask_input_size >= 64 && mask_input_size <= 256 && mask_input_size % 32 == 0,
                      core::option(mask_input_size, "mask_input_size"),
                      fmt::format("must be a multiple of 32 in [64, 256], got {}", mask_input_size));
  core::requireOption(score_threshold > 0.f && score_threshold < 1.f, core::option(score_threshold, "score_threshold"),
                      fmt::format("must be in (0, 1), got {}", score_threshold));
  core::requireOption(nms_iou > 0.f && nms_iou <= 1.f, core::option(nms_iou, "nms_iou"),
                      fmt::format("must be in (0, 1], got {}", nms_iou));
  core::requireOption(!classes.empty(), core::option(classes, "classes"),
                      "must name at least one class (e.g. [person])");
  const auto& coco = cocoClassNames();
  for (const auto& name : classes) {
    core::requireOption(
        std::find(coco.begin(), coco.end(), name) != coco.end(), core::option(classes, "classes"),
        fmt::format("names an unknown class '{}' (COCO names as in coco.names, e.g. person, chair, dog, car)", name));
  }
  core::requireInRange(box_widen_x, "box_widen_x", 0.f, 1.f);
  core::requireInRange(box_widen_y, "box_widen_y", 0.f, 1.f);
  core::requireInRange(carried_box_widen_x, "carried_box_widen_x", 0.f, 2.f);
  core::requireInRange(carried_box_widen_y, "carried_box_widen_y", 0.f, 2.f);
  core::requireOption(mask_threshold > 0.f && mask_threshold < 1.f, core::option(mask_threshold, "mask_threshold"),
                      fmt::format("must be in (0, 1), got {}", mask_threshold));
  core::requireInRange(border_crop_aspect, "border_crop_aspect", 0.f, 2.f);
  core::requireOption(min_mask_fill >= 0.f && min_mask_fill < 1.f, core::option(min_mask_fill, "min_mask_fill"),
                      fmt::format("must be in [0, 1), got {}", min_mask_fill));
  core::requireOption(depth_tolerance > 0.f, core::option(depth_tolerance, "depth_tolerance"),
                      fmt::format("must be > 0 m, got {}", depth_tolerance));
  core::requireAtLeast(max_instances, "max_instances", 1);
  core::requireOption(threads >= 0 && threads <= 64, core::option(threads, "threads"),
                      fmt::format("must be in [0, 64], got {}", threads));
  dilation.check();
}

}  // namespace amos::segmentation
