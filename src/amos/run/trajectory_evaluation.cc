#include "amos/run/trajectory_evaluation.h"

#include <utility>

#include "amos/report/ground_truth_evaluation.h"

namespace amos::run {

TrajectoryEvaluation::TrajectoryEvaluation(std::string groundtruth_file, config::GroundTruthFormat format)
    : groundtruth_file_(std::move(groundtruth_file)) {
  if (groundtruth_file_.empty()) return;
  ground_truth_ = report::readGroundTruthOrWarn(groundtruth_file_, format);
  usable_ = !ground_truth_.empty();  // a file read holds a pose at least
}

TrajectoryEvaluation::TrajectoryEvaluation(std::vector<io::StampedPose> ground_truth, std::string source,
                                           config::GroundTruthFormat format)
    : groundtruth_file_(std::move(source)),
      ground_truth_(report::groundTruthAsCameraPoses(std::move(ground_truth), format)) {}

void TrajectoryEvaluation::addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) {
  if (auto evaluation = report::evaluateOrWarn(ground_truth_, trajectory, groundtruth_file_))
    info.evaluation = std::move(evaluation);
}

}  // namespace amos::run
