#pragma once
// The SLAM core's keys: `Tracking.*`, `Matching.*`, `Relocalization.*`, `Mapping.*`, `LocalBA.*` and `Loop.*`.
// Every key is optional; its default is the value in the option struct (ORB-SLAM2's where it has one).
#include "amos/config/key_list.h"
#include "amos/loop/loop_closer.h"
#include "amos/map/map.h"
#include "amos/mapping/local_mapper.h"
#include "amos/tracking/tracker.h"

namespace amos::config {

// Tracking.*, Matching.*, Relocalization.*. `fps` (Camera.fps, read before) is the default of Tracking.maxFrames,
// as in ORB-SLAM2; `num_features` (ORBextractor.nFeatures, read before) sets the defaults of
// Tracking.closeTrackedMax and closeUntrackedMin.
KeySection trackingKeys(tracking::TrackerOptions& o, const double& fps, const int& num_features);
// Mapping.*, LocalBA.*
KeySection mappingKeys(mapping::LocalMappingOptions& o, map::CovisibilityOptions& covisibility);
// Loop.*; the fusion of loop points uses the Mapping.fuse* options read before.
KeySection loopKeys(loop::LoopClosingOptions& o, const mapping::LocalMappingOptions& mapping);

}  // namespace amos::config
