#pragma once
// Reads the SLAM core's own keys: `Tracking.*`, `Matching.*`, `Relocalization.*`, `Mapping.*`, `LocalBA.*` and `Loop.*`.
// Every key is optional; its default is the value in the option struct (ORB-SLAM2's where it has one).
#include "amos/config/yaml_reader.h"
#include "amos/loop/loop_closer.h"
#include "amos/map/map.h"
#include "amos/mapping/local_mapper.h"
#include "amos/tracking/tracker.h"

namespace amos::config {

// `fps` (Camera.fps) is the default of Tracking.maxFrames, as in ORB-SLAM2.
void readTrackingSection(YamlReader& in, double fps, tracking::TrackerOptions& o);
void readMappingSection(YamlReader& in, mapping::LocalMappingOptions& o, map::CovisibilityOptions& covisibility);
// Loop.* keys; the fusion of loop points uses the Mapping.fuse* options read before.
void readLoopSection(YamlReader& in, const mapping::LocalMappingOptions& mapping, loop::LoopClosingOptions& o);

}  // namespace amos::config
