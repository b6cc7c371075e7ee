#include "amos/evidence/evidence_sources.h"

#include "amos/evidence/baseline_tracks.h"
#include "amos/evidence/rigid_movers.h"

namespace amos::evidence {

using dynamic::EvidenceContext;
using dynamic::FrameEvidence;

DepthEvidenceSource::DepthEvidenceSource(const core::PinholeCamera& camera, const DepthEvidenceOptions& options)
    : grid_(camera, options.sample_step_px) {}

void DepthEvidenceSource::addEvidence(const EvidenceContext& context, FrameEvidence& evidence) const {
  const dynamic::FrontEndInput& in = context.input;
  const dynamic::DynamicOptions& options = context.options;
  const SuperpixelSegmentation& segmentation = context.partition.segmentation;
  const DepthFrames frames{
      {in.depth, context.T_cw}, {in.last_depth, in.T_cw_last}, {in.baseline_depth, in.T_cw_baseline}};
  const DepthComparison comparison{context.camera, options.reprojection.depth_edge_ratio, options.depth};
  const DepthEvidence depth = frameDepthEvidence(frames, grid_, segmentation, comparison);
  for (const SuperpixelDepth& sp : depth.superpixels) evidence.superpixels.depth_moving.push_back(sp.moving);
  evidence.diagnostics.depth_moving_superpixels = depth.moving_superpixels;
  evidence.depth_clusters = depthMovingClusters(depth, segmentation, context.candidates.cluster_scores,
                                                options.reprojection.min_points_per_cluster, options.depth);
}

bool BaselineTracksSource::appliesTo(const EvidenceContext& context) const {
  return !context.input.baseline_gray.empty();
}

void BaselineTracksSource::addEvidence(const EvidenceContext& context, FrameEvidence& evidence) const {
  const dynamic::FrontEndInput& in = context.input;
  const dynamic::DynamicOptions& options = context.options;
  std::vector<cv::Point2f> points;
  points.reserve(context.tracks.size());
  for (const dynamic::PointTrack& t : context.tracks) points.push_back(t.current);
  // The pipeline's stage A builds the pyramids; otherwise they are built here.
  const bool have_pyramids = !in.pyramid.empty() && !in.baseline_pyramid.empty();
  const ImagePyramid pyramid = have_pyramids ? in.pyramid : dynamic::buildPyramid(in.gray, options.tracking);
  const ImagePyramid baseline_pyramid =
      have_pyramids ? in.baseline_pyramid : dynamic::buildPyramid(in.baseline_gray, options.tracking);
  BaselineMotion& motion = evidence.baseline;
  const BaselinePyramids pyramids{pyramid, in.depth, context.T_cw, baseline_pyramid, in.T_cw_baseline};
  motion = baselineMotion(points, pyramids, context.camera, options);
  const SuperpixelSegmentation& segmentation = context.partition.segmentation;
  const int superpixels = static_cast<int>(segmentation.superpixels.size());
  evidence.diagnostics.baseline_points = static_cast<int>(motion.points.size());
  evidence.diagnostics.baseline_moving_points = motion.moving_points;
  evidence.superpixels.baseline_moving =
      baselineMovingSuperpixels(motion, segmentation.labels, superpixels, options.baseline_tracks);
  if (options.rigid_movers.grow_over_surface)
    evidence.superpixels.baseline_points = baselinePointsPerSuperpixel(motion, segmentation.labels, superpixels);
  if (!evidence.superpixels.baseline_moving.empty()) {
    const int clusters = static_cast<int>(context.candidates.cluster_scores.size());
    evidence.baseline_clusters =
        baselineMovingClusters(motion, context.regions.decision_map, clusters, options.baseline_tracks);
  }
}

bool RigidMoversSource::appliesTo(const EvidenceContext& context) const {
  return !context.input.baseline_gray.empty();
}

void RigidMoversSource::addEvidence(const EvidenceContext& context, FrameEvidence& evidence) const {
  const dynamic::FrontEndInput& in = context.input;
  const dynamic::DynamicOptions& options = context.options;
  const SuperpixelSegmentation& segmentation = context.partition.segmentation;
  const RigidMoverFrames frames{
      context.camera, {in.gray, in.depth, context.T_cw}, {in.baseline_gray, in.baseline_depth, in.T_cw_baseline}};
  const SuperpixelLabels superpixels{segmentation.labels, static_cast<int>(segmentation.superpixels.size())};
  const RigidMoverVerdict rigid =
      rigidMoverSuperpixels(evidence.baseline, frames, superpixels, options.reprojection, options.rigid_movers);
  evidence.diagnostics.rigid_movers = static_cast<int>(rigid.movers.size());
  evidence.diagnostics.rigid_superpixels = rigid.moving_superpixels;
  for (std::size_t s = 0; s < rigid.moving.size() && s < evidence.superpixels.baseline_moving.size(); ++s)
    evidence.superpixels.baseline_moving[s] = evidence.superpixels.baseline_moving[s] || rigid.moving[s];
  if (options.rigid_movers.grow_over_surface) {
    evidence.superpixels.surface_seeds.seeds = rigid.moving;
    evidence.superpixels.surface_seeds.within =
        superpixelsNearMovers(segmentation.superpixels, rigid.movers, options.rigid_movers.region_reach_px);
  }
}

std::vector<std::shared_ptr<const dynamic::EvidenceSource>> makeEvidenceSources(const core::PinholeCamera& camera,
                                                                              const dynamic::DynamicOptions& options) {
  std::vector<std::shared_ptr<const dynamic::EvidenceSource>> sources;
  if (options.depth.enabled) sources.push_back(std::make_shared<const DepthEvidenceSource>(camera, options.depth));
  if (options.baseline_tracks.enabled) {
    sources.push_back(std::make_shared<const BaselineTracksSource>());
    if (options.rigid_movers.enabled) sources.push_back(std::make_shared<const RigidMoversSource>());
  }
  return sources;
}

}  // namespace amos::evidence
