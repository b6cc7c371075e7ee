#pragma once
// The paper's two-stage anti-dynamics front end (Section III), frame in, mask out:
//   stage 1, potential motion regions: prior regions from instance segmentation (given as a mask) and
//     geometric clusters (depth-SLIC superpixels grouped by k-means) whose Cauchy-robust mean reprojection
//     error under the initial pose is high (Eq. 5-6);
//   stage 2, dynamic judgement: a fundamental matrix from last->current corner tracks (Eq. 7-8); a candidate
//     region holding epipolar violators (after boundary reassignment) is dynamic. So is a cluster whose error
//     stays high under the pose refitted on the tracks outside the candidates (reprojection_scoring.h: the
//     epipolar test is blind to motion along the epipolar lines, the depth-based error is not).
//   mask: per superpixel in and around the dynamic clusters (boundary_assignment.h), so that it follows the
//     mover's outline rather than the clusters' blobs.
//
// process() runs the stages in the paper's order; each is a function in its own file that takes the earlier stages'
// results, returns a small struct and fills its own part of DynamicDiagnostics:
//
//   prior = findPriorRegions(prior_mask);                      // frame_regions.h, III-A (each region is dynamic)
//   partition = computeGeometricPartition(bgr, depth);         // geometric_clustering.h, III-B (or given)
//   regions = findDecisionRegions(partition);                  // frame_regions.h, III-C (border blocks out)
//   tracks = trackCorners(last_gray, gray);                    // corner_tracking.h (or given)
//   candidates = scoreCandidates(tracks, regions, prior);      // candidate_scoring.h, III-C Eq. 5-6
//   confirmation = confirmUnderRefittedPose(candidates);       // pose_confirmation.h, III-C Eq. 5
//   epipolar = fitEpipolarEvidence(confirmation.fit_tracks);   // epipolar_evidence.h, III-C Eq. 7-8
//   for (source : sources) source->addEvidence(context, evidence);  // evidence_source.h: post-paper sources
//                                                              //   (src/amos/evidence/, chosen by the options)
//   voting = voteClusters(epipolar.violators, candidates, confirmation);  // cluster_voting.h, III-C
//                                                              //   (+ the sources' clusters)
//   mask |= buildDynamicMask(candidates, confirmation, epipolar, voting); // mask_building.h, III-C boundaries
//
// State: none. The caller keeps the last frame (gray, depth, pose) and the baseline frame (baseline_history.h) and
// passes them in with the current frame, so one DynamicFrontEnd can be shared, tested and benchmarked frame pair by
// frame pair. process() is const and thread-compatible (no mutable members).
#include <memory>
#include <vector>

#include "amos/core/camera.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/dynamic/evidence_source.h"
#include "amos/dynamic/front_end_types.h"

namespace amos::dynamic {

class DynamicFrontEnd {
 public:
  using EvidenceSources = std::vector<std::shared_ptr<const EvidenceSource>>;

  // `sources` are run in their order after the epipolar judgement (evidence::makeEvidenceSources builds them from
  // the options; none for the paper's front end alone).
  DynamicFrontEnd(const core::PinholeCamera& camera, const DynamicOptions& options, EvidenceSources sources);

  FrontEndResult process(const FrontEndInput& input) const;

  const DynamicOptions& options() const { return options_; }

  // The per-track border rule's band (Dynamic.Boundary.borderBlocks off): half an LK window and a pixel, the width
  // within which a track's finest-level window is cut by the image frame.
  int edgeBand() const { return options_.tracking.lk_window / 2 + 1; }

 private:
  struct Frame;  // what the stages of one process() call hand on to each other
  // The stages of process(), in the paper's order; each fills its part of the Frame and of the result.
  void maskPriorRegions(Frame& f) const;
  void partitionFrame(Frame& f) const;
  void trackCornersInto(Frame& f) const;
  void scoreAndConfirm(Frame& f) const;
  void judgeEpipolar(Frame& f) const;
  void addEvidence(Frame& f) const;
  void decideMask(Frame& f) const;
  void fillResult(Frame& f) const;

  core::PinholeCamera camera_;
  DynamicOptions options_;
  EvidenceSources sources_;
};

}  // namespace amos::dynamic
