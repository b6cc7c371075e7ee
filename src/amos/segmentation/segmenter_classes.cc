#include "amos/segmentation/segmenter_classes.h"

#include <fmt/format.h>

#include "amos/core/error.h"

namespace amos::segmentation {

const std::vector<std::string>& cocoClassNames() {
  static const std::vector<std::string> names = {
      "person", "bicycle", "car", "motorbike", "aeroplane", "bus", "train", "truck", "boat", "traffic light",
      "fire hydrant", "stop sign", "parking meter", "bench", "bird", "cat", "dog", "horse", "sheep", "cow",
      "elephant", "bear", "zebra", "giraffe", "backpack", "umbrella", "handbag", "tie", "suitcase", "frisbee",
      "skis", "snowboard", "sports ball", "kite", "baseball bat", "baseball glove", "skateboard", "surfboard",
      "tennis racket", "bottle", "wine glass", "cup", "fork", "knife", "spoon", "bowl", "banana", "apple",
      "sandwich", "orange", "broccoli", "carrot", "hot dog", "pizza", "donut", "cake", "chair", "sofa",
      "pottedplant", "bed", "diningtable", "toilet", "tvmonitor", "laptop", "mouse", "remote", "keyboard",
      "cell phone", "microwave", "oven", "toaster", "sink", "refrigerator", "book", "clock", "vase",
      "scissors", "teddy bear", "hair drier", "toothbrush"
  };
  return names;
}

int cocoClassId(const std::string& name) {
  const auto& names = cocoClassNames();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  throw core::Error(fmt::format(
      "Segmentation.classes: unknown class '{}' (COCO names as in coco.names, e.g. person, chair, dog, car)", name));
}

std::string cocoClassName(int class_id) {
  const auto& names = cocoClassNames();
  if (class_id >= 0 && class_id < static_cast<int>(names.size())) return names[class_id];
  return fmt::format("class{}", class_id);
}

std::vector<std::string> movableCocoClasses() {
  return {"person", "bicycle", "car",  "motorbike", "bus",     "truck",    "bird",    "cat",      "dog",
          "horse",  "sheep",   "cow",  "backpack",  "umbrella", "handbag", "suitcase", "sports ball", "chair"};
}

}  // namespace amos::segmentation
