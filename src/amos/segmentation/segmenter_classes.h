#pragma once
// COCO class names (the 80 classes NanoDet and most instance segmenters are trained on), in the order of the
// networks' class outputs, and a lookup by name for the Segmentation.classes setting.
#include <string>
#include <vector>

namespace amos::segmentation {

// The 80 COCO class names, index = class id (0 = "person"), spelt as in the models' coco.names.
const std::vector<std::string>& cocoClassNames();

// Class id of a COCO name (case-sensitive, as in coco.names); throws core::Error listing a few valid names when
// the name is unknown.
int cocoClassId(const std::string& name);

// Name of a class id, or "class<id>" for ids outside the table.
std::string cocoClassName(int class_id);

// Movable COCO classes a user may want to mask besides people (vehicles, animals, carried objects). Not the
// default: the paper masks people only; everything else is left to the geometric stage.
std::vector<std::string> movableCocoClasses();

}  // namespace amos::segmentation
