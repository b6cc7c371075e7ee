#include "amos/run/trajectory_evaluation.h"

#include <spdlog/spdlog.h>

#include <utility>

#include "amos/core/error.h"
#include "amos/eval/bonn_ground_truth.h"
#include "amos/eval/evaluate.h"

namespace amos::run {

TrajectoryEvaluation::TrajectoryEvaluation(std::string groundtruth_file, config::GroundTruthFormat format)
    : groundtruth_file_(std::move(groundtruth_file)), format_(format) {}

std::vector<io::StampedPose> TrajectoryEvaluation::readGroundTruth() const {
  std::vector<io::StampedPose> gt = io::readTumTrajectory(groundtruth_file_);
  if (format_ == config::GroundTruthFormat::kBonn) gt = eval::bonnMarkerToCamera(gt);
  return gt;
}

std::vector<io::StampedPose> TrajectoryEvaluation::groundTruthForObservers() const {
  if (groundtruth_file_.empty()) return {};
  try {
    return readGroundTruth();
  } catch (const core::Error&) {
    return {};
  }
}

void TrajectoryEvaluation::addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) {
  if (groundtruth_file_.empty() || trajectory.size() < 2) return;
  const std::vector<io::StampedPose> gt = readGroundTruth();
  try {
    info.evaluation = eval::evaluate(gt, trajectory);
  } catch (const core::Error& e) {
    spdlog::warn("no evaluation against {}: {}", groundtruth_file_, e.what());
  }
}

}  // namespace amos::run
