#include "amos/report/ground_truth_evaluation.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <utility>

#include "amos/eval/bonn_ground_truth.h"

namespace amos::report {

std::vector<io::StampedPose> groundTruthAsCameraPoses(std::vector<io::StampedPose> ground_truth,
                                                      config::GroundTruthFormat format) {
  if (format == config::GroundTruthFormat::kBonn) return eval::bonnMarkerToCamera(ground_truth);
  return ground_truth;
}

std::vector<io::StampedPose> readGroundTruthOrWarn(const std::string& file, config::GroundTruthFormat format) {
  try {
    return groundTruthAsCameraPoses(io::readTumTrajectoryWithPoses(file, "ground-truth file"), format);
  } catch (const std::exception& e) {
    spdlog::warn("{}; the run goes on without evaluation (fix the file and run `amos-slam eval` on the outputs)",
                 e.what());
    return {};
  }
}

std::optional<eval::EvaluationResult> evaluateOrWarn(const std::vector<io::StampedPose>& ground_truth,
                                                     const std::vector<io::StampedPose>& trajectory,
                                                     const std::string& source) {
  if (ground_truth.empty() || trajectory.size() < 2) return std::nullopt;
  try {
    return eval::evaluate(ground_truth, trajectory);
  } catch (const std::exception& e) {
    spdlog::warn("no evaluation against {}: {}", source, e.what());
    return std::nullopt;
  }
}

}  // namespace amos::report
