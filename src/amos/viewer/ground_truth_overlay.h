#pragma once
// The ground truth drawn beside the estimate: ATE's alignment (estimate -> ground truth, eval/alignment.h)
// inverted, so the ground truth is shown in the map's frame, where the map points and keyframes are.
#include <optional>
#include <vector>

#include "amos/eval/alignment.h"
#include "amos/io/trajectory.h"
#include "amos/viewer/live_update.h"

namespace amos::viewer {

// Ground-truth camera centres in the estimate's frame.
std::vector<TrajectoryPoint> groundTruthInMapFrame(const std::vector<io::StampedPose>& ground_truth,
                                                   const eval::Alignment& alignment);

// ATE's alignment of `estimate` onto `ground_truth` (rigid), or nothing while fewer than three poses associate.
std::optional<eval::Alignment> alignEstimate(const std::vector<io::StampedPose>& ground_truth,
                                             const std::vector<io::StampedPose>& estimate);

}  // namespace amos::viewer
