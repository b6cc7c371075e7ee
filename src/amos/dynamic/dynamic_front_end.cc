#include "amos/dynamic/dynamic_front_end.h"

#include <algorithm>
#include <opencv2/core.hpp>
#include <utility>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/dynamic/candidate_scoring.h"
#include "amos/dynamic/cluster_voting.h"
#include "amos/dynamic/epipolar_evidence.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/mask_building.h"
#include "amos/dynamic/pose_confirmation.h"

namespace amos::dynamic {

DynamicFrontEnd::DynamicFrontEnd(const core::PinholeCamera& camera, const DynamicOptions& options,
                                 EvidenceSources sources)
    : camera_(camera), options_(options), sources_(std::move(sources)) {
  options_.check();
  for (const auto& source : sources_) core::require(source != nullptr, "DynamicFrontEnd: an evidence source is null");
}

namespace {

void checkInput(const FrontEndInput& in) {
  core::require(!in.gray.empty() && in.gray.type() == CV_8UC1, "DynamicFrontEnd: gray must be CV_8UC1");
  const cv::Size size = in.gray.size();
  core::require(in.bgr.type() == CV_8UC3 && in.bgr.size() == size, "DynamicFrontEnd: bgr must be CV_8UC3, gray's size");
  core::require(in.depth.type() == CV_32F && in.depth.size() == size,
                "DynamicFrontEnd: depth must be CV_32F metres, gray's size");
  core::require(in.prior_mask.empty() || (in.prior_mask.type() == CV_8UC1 && in.prior_mask.size() == size),
                "DynamicFrontEnd: prior_mask must be empty or CV_8UC1 of the image size");
  core::require(in.last_mask.empty() || (in.last_mask.type() == CV_8UC1 && in.last_mask.size() == size),
                "DynamicFrontEnd: last_mask must be empty or CV_8UC1 of the image size");
  core::require(in.baseline_depth.empty() || (in.baseline_depth.type() == CV_32F && in.baseline_depth.size() == size),
                "DynamicFrontEnd: baseline_depth must be empty or CV_32F of the image size");
  core::require(in.baseline_gray.empty() || (in.baseline_gray.type() == CV_8UC1 && in.baseline_gray.size() == size),
                "DynamicFrontEnd: baseline_gray must be empty or CV_8UC1 of the image size");
  if (!in.last_gray.empty()) {
    core::require(in.last_gray.type() == CV_8UC1 && in.last_gray.size() == size,
                  "DynamicFrontEnd: last_gray must be CV_8UC1 of the image size");
    core::require(in.last_depth.type() == CV_32F && in.last_depth.size() == size,
                  "DynamicFrontEnd: last_depth must be CV_32F of the image size");
  }
}

// Marks the clusters `moved` names dynamic; returns how many were not already.
int addClusters(const std::vector<bool>& moved, std::vector<bool>& dynamic_cluster) {
  int added = 0;
  for (std::size_t c = 0; c < moved.size() && c < dynamic_cluster.size(); ++c)
    if (moved[c] && !dynamic_cluster[c]) {
      dynamic_cluster[c] = true;
      ++added;
    }
  return added;
}

}  // namespace

// What the stages of one process() call hand on to each other. References to the input and the result, which the
// stages fill; the intermediate results by value (moved into the result at the end, never copied).
struct DynamicFrontEnd::Frame {
  Frame(const FrontEndInput& input, FrontEndResult& result)
      : in(input), out(result), diag(result.diagnostics), evidence(result.diagnostics) {}

  const FrontEndInput& in;
  FrontEndResult& out;
  DynamicDiagnostics& diag;
  core::Stopwatch stage;  // restarted by lap()

  PriorRegions prior;
  GeometricPartition computed;  // when the caller gave no partition
  const GeometricPartition* partition = nullptr;
  DecisionRegions regions;
  CandidateScoring candidates;
  PoseConfirmation confirmation;
  EpipolarEvidence epipolar;
  FrameEvidence evidence;  // the evidence sources'
  ClusterVoting voting;

  // Records the time since the last lap under `name`.
  void lap(const char* name) {
    out.timings_ms.emplace_back(name, stage.elapsedMs());
    stage.restart();
  }
};

FrontEndResult DynamicFrontEnd::process(const FrontEndInput& in) const {
  checkInput(in);
  core::Stopwatch total;
  FrontEndResult out;
  out.mask = cv::Mat(in.gray.size(), CV_8U, cv::Scalar(0));
  Frame f(in, out);
  maskPriorRegions(f);
  const DynamicMode mode = options_.mode;
  if ((mode == DynamicMode::kGeometry || mode == DynamicMode::kFull) && !in.last_gray.empty()) {
    out.diagnostics.geometry_ran = true;
    f.stage.restart();
    partitionFrame(f);        // III-B
    trackCornersInto(f);      // last -> current correspondences
    scoreAndConfirm(f);       // III-C, Eq. 5-6
    judgeEpipolar(f);         // III-C, Eq. 7-8
    addEvidence(f);           // post-paper: the evidence sources (evidence_source.h)
    decideMask(f);            // III-C, the decision and the boundaries
    fillResult(f);
  }
  out.timings_ms.emplace_back("total", total.elapsedMs());
  return out;
}

// Prior regions (III-A): connected components of the (already dilated) segmentation mask, every one of them dynamic.
void DynamicFrontEnd::maskPriorRegions(Frame& f) const {
  const DynamicMode mode = options_.mode;
  const bool use_prior = (mode == DynamicMode::kPrior || mode == DynamicMode::kFull) && !f.in.prior_mask.empty();
  if (!use_prior) return;
  f.prior = findPriorRegions(f.in.prior_mask);
  f.diag.prior_regions = f.prior.count;
  f.out.mask.setTo(255, f.in.prior_mask != 0);
  f.diag.dynamic_prior_regions = f.prior.count;
}

// Stage 1a (III-B): superpixels and geometric clusters of the current frame; border blocks take no part in the
// decisions (III-C).
void DynamicFrontEnd::partitionFrame(Frame& f) const {
  if (f.in.partition == nullptr)
    f.computed = computeGeometricPartition(f.in.bgr, f.in.depth, options_.superpixel, options_.cluster);
  f.partition = f.in.partition ? f.in.partition : &f.computed;
  const GeometricPartition& partition = *f.partition;
  f.out.timings_ms.emplace_back("superpixels", partition.superpixel_ms);
  f.stage.restart();
  f.diag.superpixels = static_cast<int>(partition.segmentation.superpixels.size());
  f.diag.clusters = clusterCount(partition.segmentation);
  f.regions =
      options_.boundary.border_blocks
          ? findDecisionRegions(partition.segmentation, partition.cluster_map, options_.boundary.border_margin_px)
          : findEdgeDecisionRegions(partition.segmentation, partition.cluster_map, edgeBand());
  f.out.timings_ms.emplace_back("clusters", partition.cluster_ms + f.stage.elapsedMs());
  f.stage.restart();
}

// Correspondences last -> current.
void DynamicFrontEnd::trackCornersInto(Frame& f) const {
  const FrontEndInput& in = f.in;
  std::vector<PointTrack>& tracks = f.out.tracks;
  tracks = in.tracks ? *in.tracks : trackCorners(in.last_gray, in.gray, options_.tracking);
  if (!options_.boundary.border_blocks) {
    // The per-track border rule at the other end: the edge band of the decision map takes the tracks that end near
    // the image edge out of the decisions; a track that started there had its LK template cut by the frame (a
    // camera turning brings such points inwards within a frame) and goes too.
    const float band = static_cast<float>(edgeBand());
    const float max_x = static_cast<float>(in.gray.cols - 1) - band, max_y = static_cast<float>(in.gray.rows - 1) - band;
    tracks.erase(std::remove_if(tracks.begin(), tracks.end(),
                                [&](const PointTrack& t) {
                                  return t.last.x < band || t.last.y < band || t.last.x > max_x || t.last.y > max_y;
                                }),
                 tracks.end());
  }
  f.diag.tracks = static_cast<int>(tracks.size());
  f.lap("tracking");
}

// Stage 1b (III-C, Eq. 5-6): the potential motion regions from the reprojection errors under the initial pose, and
// every cluster judged again under the pose refitted without them.
void DynamicFrontEnd::scoreAndConfirm(Frame& f) const {
  f.candidates = scoreCandidates(f.out.tracks, f.in, {f.regions.decision_map, f.diag.clusters, f.prior}, camera_,
                                 options_, f.diag);
  f.confirmation = confirmUnderRefittedPose(f.out.tracks, f.candidates, f.in.T_cw_last, f.in.T_cw_initial, camera_,
                                            options_.reprojection, f.diag);
  f.lap("reprojection");
}

// Stage 2 (III-C, Eq. 7-8): fundamental matrix on the undistorted tracks outside the potential motion regions,
// epipolar distance of every track.
void DynamicFrontEnd::judgeEpipolar(Frame& f) const {
  f.epipolar = fitEpipolarEvidence(f.out.tracks, f.confirmation.fit_tracks, camera_, options_.epipolar, f.diag);
  f.lap("epipolar");
}

// The evidence sources, in their order; each is timed under its name.
void DynamicFrontEnd::addEvidence(Frame& f) const {
  const EvidenceContext context{f.in,    f.out.tracks,          *f.partition, f.regions, f.candidates,
                                f.confirmation.refit.T_cw, camera_, options_};
  for (const auto& source : sources_) {
    if (!source->appliesTo(context)) continue;
    source->addEvidence(context, f.evidence);
    f.lap(source->name());
  }
}

// Decision: the epipolar violators vote for clusters (and the evidence sources add theirs), then the mask follows the
// dynamic clusters per superpixel (or covers them whole).
void DynamicFrontEnd::decideMask(Frame& f) const {
  DynamicDiagnostics& diag = f.diag;
  f.voting = voteClusters(f.epipolar.violators, f.regions.decision_map, f.candidates.cluster_scores,
                          f.confirmation.confirmed, options_, diag);
  std::vector<bool>& dynamic_cluster = f.voting.dynamic_cluster;
  const FrameEvidence& evidence = f.evidence;
  diag.depth_dynamic_clusters = addClusters(evidence.depth_clusters, dynamic_cluster);
  diag.baseline_dynamic_clusters = addClusters(evidence.baseline_clusters, dynamic_cluster);
  diag.dynamic_clusters += diag.depth_dynamic_clusters + diag.baseline_dynamic_clusters;
  const MaskStages stages{f.in,           f.out.tracks,   *f.partition, f.regions,
                          f.candidates,   f.confirmation, f.epipolar,   f.voting};
  const DynamicMask mask = buildDynamicMask(stages, evidence.superpixels, options_, diag);
  cv::bitwise_or(f.out.mask, mask.mask, f.out.mask);
  f.lap("decision");
}

// The geometric detail of the result (moved, not copied, from the stages' results).
void DynamicFrontEnd::fillResult(Frame& f) const {
  FrontEndResult& out = f.out;
  out.superpixel_labels = f.partition->segmentation.labels;
  out.cluster_map = f.partition->cluster_map;
  out.cluster_scores = std::move(f.candidates.cluster_scores);
  out.reprojection_error_px = std::move(f.candidates.errors_px);
  out.confirm_scores = std::move(f.confirmation.confirm_scores);
  out.judged_error_px = residualNorms(f.confirmation.residuals);
  out.T_cw_judged = f.confirmation.refit.T_cw;
  out.dynamic_cluster = std::move(f.voting.dynamic_cluster);
  out.epipolar_distance_px = std::move(f.epipolar.distance_px);
  out.baseline_bar_px = f.evidence.baseline.bar_px;
  out.baseline_points = std::move(f.evidence.baseline.points);
}

}  // namespace amos::dynamic
