#pragma once
// The evaluation of a run as an observer: at the end, the final trajectory against the sequence's ground truth
// (ATE / RPE, eval/evaluate.h; Bonn marker poses converted to camera poses first), into RunInfo::evaluation.
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/io/trajectory.h"
#include "amos/run/run_observer.h"

namespace amos::run {

class TrajectoryEvaluation : public RunObserver {
 public:
  // `groundtruth_file`: "" = none (nothing is evaluated).
  TrajectoryEvaluation(std::string groundtruth_file, config::GroundTruthFormat format);

  // The ground truth as camera poses for the observers (RunStart::ground_truth); empty when there is none or it
  // cannot be read (the evaluation at the end reports that).
  std::vector<io::StampedPose> groundTruthForObservers() const;

  void onFrame(const FrameSnapshot& frame) override { (void)frame; }
  // With at least two poses: reads the ground truth (an unreadable file throws core::Error) and evaluates; a
  // trajectory that cannot be evaluated against it (too few matching stamps) is a warning, without evaluation.
  void addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) override;

 private:
  std::vector<io::StampedPose> readGroundTruth() const;

  std::string groundtruth_file_;
  config::GroundTruthFormat format_;
};

}  // namespace amos::run
