#pragma once
// A run's evaluation against ground truth (ATE / RPE, eval/evaluate.h), shared by `amos-slam run` (an observer,
// run/trajectory_evaluation.h) and amos::Slam::writeOutputs (RunDescription::groundtruth_file). Nothing here
// costs a run its outputs: a ground truth that cannot be read, or an evaluation that fails, is a warning and the
// outputs are written without evaluation.
#include <optional>
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/eval/evaluate.h"
#include "amos/io/trajectory.h"

namespace amos::report {

// The ground truth's poses as camera poses: Bonn marker poses (`format` kBonn) converted, TUM ones as they are.
std::vector<io::StampedPose> groundTruthAsCameraPoses(std::vector<io::StampedPose> ground_truth,
                                                      config::GroundTruthFormat format);
// A ground-truth file read and checked (io::readTumTrajectoryWithPoses) as camera poses; empty after a warning
// naming the file and the line when it cannot be read.
std::vector<io::StampedPose> readGroundTruthOrWarn(const std::string& file, config::GroundTruthFormat format);
// `trajectory` against `ground_truth` (camera poses); nullopt without a ground truth or with fewer than two poses,
// and after a warning naming `source` when the evaluation fails (too few matching stamps, ...).
std::optional<eval::EvaluationResult> evaluateOrWarn(const std::vector<io::StampedPose>& ground_truth,
                                                     const std::vector<io::StampedPose>& trajectory,
                                                     const std::string& source);

}  // namespace amos::report
