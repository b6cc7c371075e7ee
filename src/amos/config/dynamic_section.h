#pragma once
// The `Dynamic.*` (paper Sec. III front end) and `Segmentation.*` (prior-object segmenter) keys.
#include "amos/config/key_list.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/segmentation/segmenter_options.h"

namespace amos::config {

KeySection dynamicKeys(dynamic::DynamicOptions& o);
KeySection segmentationKeys(segmentation::SegmenterOptions& o);

}  // namespace amos::config
