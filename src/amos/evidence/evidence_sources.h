#pragma once
// The evidence sources added after the paper (dynamic/evidence_source.h), each behind the one interface, and the
// factory that picks them from the options. DynamicFrontEnd never names a source; its callers build the list here.
//   DepthEvidenceSource   (Dynamic.Depth.enabled): superpixels whose depth moved under the judged pose
//                         (depth_evidence.h), and the clusters they make dynamic;
//   BaselineTracksSource  (Dynamic.BaselineTracks.enabled): the tracked points against the frame
//                         Dynamic.Depth.baselineFrames back (baseline_tracks.h), for movers too slow for one frame;
//   RigidMoversSource     (Dynamic.RigidMovers.enabled, with the baseline tracks): the moving long-baseline points'
//                         rigid motions and the superpixels that follow one (rigid_movers.h).
#include <memory>
#include <vector>

#include "amos/core/camera.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/dynamic/evidence_source.h"
#include "amos/evidence/depth_evidence.h"

namespace amos::evidence {

class DepthEvidenceSource : public dynamic::EvidenceSource {
 public:
  DepthEvidenceSource(const core::PinholeCamera& camera, const DepthEvidenceOptions& options);
  const char* name() const override { return "depth"; }
  void addEvidence(const dynamic::EvidenceContext& context, dynamic::FrameEvidence& evidence) const override;

 private:
  DepthSampleGrid grid_;
};

class BaselineTracksSource : public dynamic::EvidenceSource {
 public:
  const char* name() const override { return "baseline_tracks"; }
  bool appliesTo(const dynamic::EvidenceContext& context) const override;  // with a baseline frame
  void addEvidence(const dynamic::EvidenceContext& context, dynamic::FrameEvidence& evidence) const override;
};

// Reads the long-baseline motion, so it runs after a BaselineTracksSource.
class RigidMoversSource : public dynamic::EvidenceSource {
 public:
  const char* name() const override { return "rigid_movers"; }
  bool appliesTo(const dynamic::EvidenceContext& context) const override;  // with a baseline frame
  void addEvidence(const dynamic::EvidenceContext& context, dynamic::FrameEvidence& evidence) const override;
};

// The sources the options turn on, in the order they must run: depth, long-baseline tracks, rigid movers.
std::vector<std::shared_ptr<const dynamic::EvidenceSource>> makeEvidenceSources(const core::PinholeCamera& camera,
                                                                              const dynamic::DynamicOptions& options);

}  // namespace amos::evidence
