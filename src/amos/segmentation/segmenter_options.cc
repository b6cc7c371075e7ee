#include "amos/segmentation/segmenter_options.h"

#include <fmt/format.h>

#include "amos/core/error.h"
#include "amos/segmentation/segmenter_classes.h"

namespace amos::segmentation {

using core::require;

void MaskDilationOptions::check() const {
  require(size >= 0 && size <= 255 && (size <= 1 || size % 2 == 1),
          fmt::format("Segmentation.dilation_size must be 0, 1 or an odd number up to 255, got {}", size));
  require(shape == "ellipse" || shape == "rect" || shape == "cross",
          fmt::format("Segmentation.dilation_shape must be ellipse, rect or cross, got '{}'", shape));
}

void SegmenterOptions::check() const {
  require(!backend.empty(), "Segmentation.backend must not be empty");
  require(input_size == 320 || input_size == 416,
          fmt::format("Segmentation.input_size must be 320 or 416 (the available NanoDet exports), got {}", input_size));
  require(input_shape == "frame" || input_shape == "square",
          fmt::format("Segmentation.input_shape must be frame or square, got '{}'", input_shape));
  require(mask_input_size >= 64 && mask_input_size <= 256 && mask_input_size % 32 == 0,
          fmt::format("Segmentation.mask_input_size must be a multiple of 32 in [64, 256], got {}", mask_input_size));
  require(score_threshold > 0.f && score_threshold < 1.f,
          fmt::format("Segmentation.score_threshold must be in (0, 1), got {}", score_threshold));
  require(nms_iou > 0.f && nms_iou <= 1.f, fmt::format("Segmentation.nms_iou must be in (0, 1], got {}", nms_iou));
  require(!classes.empty(), "Segmentation.classes must name at least one class (e.g. [person])");
  for (const auto& name : classes) cocoClassId(name);  // throws naming Segmentation.classes
  require(box_widen_x >= 0.f && box_widen_x <= 1.f,
          fmt::format("Segmentation.box_widen_x must be in [0, 1], got {}", box_widen_x));
  require(box_widen_y >= 0.f && box_widen_y <= 1.f,
          fmt::format("Segmentation.box_widen_y must be in [0, 1], got {}", box_widen_y));
  require(mask_threshold > 0.f && mask_threshold < 1.f,
          fmt::format("Segmentation.mask_threshold must be in (0, 1), got {}", mask_threshold));
  require(border_crop_aspect >= 0.f && border_crop_aspect <= 2.f,
          fmt::format("Segmentation.border_crop_aspect must be in [0, 2], got {}", border_crop_aspect));
  require(min_mask_fill >= 0.f && min_mask_fill < 1.f,
          fmt::format("Segmentation.min_mask_fill must be in [0, 1), got {}", min_mask_fill));
  require(depth_tolerance > 0.f, fmt::format("Segmentation.depth_tolerance must be > 0 m, got {}", depth_tolerance));
  require(max_instances >= 1, fmt::format("Segmentation.max_instances must be >= 1, got {}", max_instances));
  require(threads >= 0 && threads <= 64, fmt::format("Segmentation.threads must be in [0, 64], got {}", threads));
  dilation.check();
}

}  // namespace amos::segmentation
