#include "amos/run/trajectory_evaluation.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <utility>

#include "amos/core/error.h"
#include "amos/eval/bonn_ground_truth.h"
#include "amos/eval/evaluate.h"

namespace amos::run {

TrajectoryEvaluation::TrajectoryEvaluation(std::string groundtruth_file, config::GroundTruthFormat format)
    : groundtruth_file_(std::move(groundtruth_file)) {
  if (groundtruth_file_.empty()) return;
  try {
    ground_truth_ = io::readTumTrajectoryWithPoses(groundtruth_file_, "ground-truth file");
    if (format == config::GroundTruthFormat::kBonn) ground_truth_ = eval::bonnMarkerToCamera(ground_truth_);
  } catch (const std::exception& e) {
    spdlog::warn("{}; the run goes on without evaluation (fix the file and run `amos-slam eval` on the outputs)",
                 e.what());
    ground_truth_.clear();
    usable_ = false;
  }
}

TrajectoryEvaluation::TrajectoryEvaluation(std::vector<io::StampedPose> ground_truth, std::string source,
                                           config::GroundTruthFormat format)
    : groundtruth_file_(std::move(source)), ground_truth_(std::move(ground_truth)) {
  if (format == config::GroundTruthFormat::kBonn) ground_truth_ = eval::bonnMarkerToCamera(ground_truth_);
}

void TrajectoryEvaluation::addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) {
  if (ground_truth_.empty() || trajectory.size() < 2) return;
  try {
    info.evaluation = eval::evaluate(ground_truth_, trajectory);
  } catch (const std::exception& e) {
    spdlog::warn("no evaluation against {}: {}", groundtruth_file_, e.what());
  }
}

}  // namespace amos::run
