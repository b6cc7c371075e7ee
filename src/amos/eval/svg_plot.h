#pragma once
// A dependency-free SVG picture of an evaluation: left, the top view of the ground truth and the aligned estimate
// (the two world axes along which the ground truth extends most, equal scale on both, axis names in the labels),
// with thin red lines joining associated pairs; right, the ATE error of each associated pair over time with its
// RMSE as a dashed line. The title carries ATE RMSE and RPE.
#include <string>
#include <vector>

#include "amos/eval/evaluate.h"
#include "amos/io/trajectory.h"

namespace amos::eval {

// gt and est as given to evaluate(); only the ground truth within the associated time span is drawn, the
// estimate is drawn after applying result.alignment. `title` is the first line of the title (may be empty).
std::string renderEvaluationSvg(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est,
                                const EvaluationResult& result, const std::string& title);

// Writes renderEvaluationSvg(...) to `path`; throws core::Error when the file cannot be written.
void writeEvaluationSvg(const std::string& path, const std::vector<io::StampedPose>& gt,
                        const std::vector<io::StampedPose>& est, const EvaluationResult& result,
                        const std::string& title);

}  // namespace amos::eval
