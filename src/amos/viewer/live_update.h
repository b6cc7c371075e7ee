#pragma once
// One change of what the viewer shows: the unit the publisher produces, LiveState applies and the browsers
// receive (as JSON, delta_json.h).
#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "amos/viewer/map_delta.h"

namespace amos::viewer {

struct TrajectoryPoint {
  double timestamp = 0;
  Eigen::Vector3f position = Eigen::Vector3f::Zero();  // camera centre, world
};

struct LiveUpdate {
  std::optional<nlohmann::json> info;     // the run: sequence, mode, camera, frames (replaces)
  std::optional<nlohmann::json> frame;    // the current frame's status (delta_json.h: frameStatusJson)
  std::vector<TrajectoryPoint> trajectory;  // appended to the trajectory ...
  bool trajectory_reset = false;            // ... or, when set, replacing it (the final, corrected one)
  std::optional<std::vector<TrajectoryPoint>> ground_truth;  // aligned to the estimate (replaces)
  MapDelta map;
  std::optional<nlohmann::json> summary;  // end of the run: figures of stats.json
  bool frame_image = false;               // a new frame image is available (/api/frame.jpg)
};

}  // namespace amos::viewer
