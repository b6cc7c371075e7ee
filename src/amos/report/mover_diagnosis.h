#pragma once
// `amos-slam diagnose-movers`: runs the geometric front end (paper III-B/III-C) frame pair by frame pair on a
// synthetic sequence with its ground-truth poses and instance masks, and says per moving instance and frame what
// each stage made of it (dynamic/mover_diagnostics.h). The poses are the truth, so what it shows is the
// segmentation alone, not the tracking that feeds it: T_cw_last = truth of the last frame, the initial pose =
// constant velocity from the last two true poses (the pipeline's model 3), or the truth itself with exact_initial.
#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>

#include <opencv2/core.hpp>

#include "amos/config/settings.h"
#include "amos/dynamic/dynamic_front_end.h"

namespace amos::report {

struct MoverDiagnosisOptions {
  std::string sequence_dir;
  int first_frame = 0;
  int last_frame = -1;         // inclusive; -1 = to the end
  bool exact_initial = false;  // initial pose = the true pose (else constant velocity from the truth)
  bool per_frame = true;       // a line per mover and frame (else the summary only)
  // When set, a picture of each judged frame's decision is written there (<frame index>.png, see
  // decisionPicture): where the mask is right, where it is wrong, the dynamic clusters and the tracks' errors.
  std::string images_dir;
};

struct MoverDiagnosisSummary {
  struct PerInstance {
    std::string name;
    int frames = 0;
    std::int64_t pixels = 0, marked = 0;
    std::map<std::string, int> causes;  // frames per cause
  };
  std::map<std::uint16_t, PerInstance> instances;
};

// A picture of one frame's decision: the frame (bgr) dimmed, the final mask against the truth (truth_ids: CV_16U,
// 0 = static) tinted green where a mover is marked, red where the static world is, blue where a mover is missed;
// the outlines of the dynamic clusters in white; every track's end coloured by its error under the judged pose:
// green below the confirmation threshold (at least 0.5 px), yellow below three times it, red beyond, grey unscored.
cv::Mat decisionPicture(const cv::Mat& bgr, const cv::Mat& truth_ids, const dynamic::FrontEndResult& result);

// Prints a table (per_frame) and a summary per instance to `out`; progress on stderr. Throws core::Error when the
// sequence has no ground-truth poses or masks.
MoverDiagnosisSummary diagnoseSequenceMovers(const config::Settings& settings, const MoverDiagnosisOptions& options,
                                             std::ostream& out);

}  // namespace amos::report
