#pragma once
// Reads the `Dynamic.*` (paper Sec. III front end) and `Segmentation.*` (prior-object segmenter) keys.
#include "amos/config/yaml_reader.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/segmentation/segmenter_options.h"

namespace amos::config {

void readDynamicSection(YamlReader& in, dynamic::DynamicOptions& o);
void readSegmentationSection(YamlReader& in, segmentation::SegmenterOptions& o);

}  // namespace amos::config
