#pragma once
// The evidence sources added after the paper, behind one interface: each reads what the paper's stages found in a
// frame (EvidenceContext) and adds its own evidence of motion (FrameEvidence): moving superpixels for the mask,
// dynamic clusters for the decision. DynamicFrontEnd calls its sources in order after the epipolar judgement and
// never names one; the concrete sources (depth evidence, long-baseline tracks, rigid movers) live in
// src/amos/evidence/, whose makeEvidenceSources builds the list from DynamicOptions. Like the front end, a source
// is const and stateless between frames, so one list can be shared by threads.
#include <vector>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dynamic/baseline_motion.h"
#include "amos/dynamic/candidate_scoring.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/front_end_types.h"
#include "amos/dynamic/geometric_clustering.h"
#include "amos/dynamic/mask_building.h"

namespace amos::dynamic {

// What the sources read: the frame and what the paper's stages made of it (references, valid during one call).
struct EvidenceContext {
  const FrontEndInput& input;
  const std::vector<PointTrack>& tracks;  // last -> current, after the border rule
  const GeometricPartition& partition;    // superpixels and clusters of the current frame
  const DecisionRegions& regions;         // decision_map: cluster per pixel, border blocks out
  const CandidateScoring& candidates;     // the clusters' scores (a scored cluster is the paper's to judge)
  const core::SE3& T_cw;                  // the judged pose (refitted without the candidates)
  const core::PinholeCamera& camera;
  const DynamicOptions& options;
};

// What the sources contribute, in the order they run (a later source reads an earlier one's, e.g. the rigid movers
// the long-baseline motion). Per-superpixel vectors are empty when no source filled them.
struct FrameEvidence {
  explicit FrameEvidence(DynamicDiagnostics& diag) : diagnostics(diag) {}

  DynamicDiagnostics& diagnostics;        // the sources' counters (depth_moving_superpixels, baseline_points, ...)
  SuperpixelEvidence superpixels;         // the mask's seeds (depth_moving, baseline_moving) and surface growth
  std::vector<bool> depth_clusters;       // per cluster: dynamic by the depth evidence
  BaselineMotion baseline;                // the tracked points against the baseline frame
  std::vector<bool> baseline_clusters;    // per cluster: dynamic by the long-baseline points
};

class EvidenceSource {
 public:
  virtual ~EvidenceSource();
  // The name its time is recorded under in FrontEndResult::timings_ms.
  virtual const char* name() const = 0;
  // Whether the frame carries what the source reads (e.g. a baseline frame); a source that does not apply is neither
  // run nor timed.
  virtual bool appliesTo(const EvidenceContext& context) const;
  virtual void addEvidence(const EvidenceContext& context, FrameEvidence& evidence) const = 0;
};

}  // namespace amos::dynamic
