#pragma once
// The evaluation of a run as an observer: at the end, the final trajectory against the sequence's ground truth
// (ATE / RPE, eval/evaluate.h; Bonn marker poses converted to camera poses first), into RunInfo::evaluation, by
// report/ground_truth_evaluation.h (which amos::Slam::writeOutputs evaluates with too).
// The ground truth is read and checked when the observer is made, before the first frame: a file that cannot be
// read (a bad first line, a truncated last line, a field that is not a number, no pose) is a warning naming the
// file and the line, and the run goes on without evaluation. Nothing the evaluation does costs the run its
// outputs: an evaluation that fails at the end is a warning too.
#include <string>
#include <vector>

#include "amos/config/settings.h"
#include "amos/io/trajectory.h"
#include "amos/run/run_observer.h"

namespace amos::run {

class TrajectoryEvaluation : public RunObserver {
 public:
  // `groundtruth_file`: "" = none (nothing is evaluated). Reads it (see above).
  TrajectoryEvaluation(std::string groundtruth_file, config::GroundTruthFormat format);
  // Ground truth read already (a bag's topic, run/bag_source.h), named `source` in messages; converted as a file's
  // of `format` is.
  TrajectoryEvaluation(std::vector<io::StampedPose> ground_truth, std::string source,
                       config::GroundTruthFormat format);

  // The ground truth as camera poses for the observers (RunStart::ground_truth); empty when there is none or it
  // cannot be read.
  const std::vector<io::StampedPose>& groundTruthForObservers() const { return ground_truth_; }
  // False when there was a ground-truth file that could not be read (warned about).
  bool usable() const { return usable_; }

  void onFrame(const FrameSnapshot& frame) override { (void)frame; }
  // With at least two poses and a usable ground truth: evaluates. Any error of the evaluation (too few matching
  // stamps, ...) is a warning, without evaluation; it never throws.
  void addToInfo(const std::vector<io::StampedPose>& trajectory, report::RunInfo& info) override;

 private:
  std::string groundtruth_file_;
  std::vector<io::StampedPose> ground_truth_;
  bool usable_ = true;
};

}  // namespace amos::run
