#include "amos/dynamic/mover_diagnostics.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "amos/core/error.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/robust_scale.h"

namespace amos::dynamic {

namespace {
double median(std::vector<double> v) { return v.empty() ? 0 : upperMedian(std::move(v)); }
}  // namespace

std::vector<MoverFrameDiagnosis> diagnoseMovers(const FrontEndResult& out, const cv::Mat& instances,
                                                const std::vector<bool>& moving, const DynamicOptions& options) {
  core::require(instances.type() == CV_16UC1 && instances.size() == out.mask.size(),
                "diagnoseMovers: instances must be CV_16U of the mask's size");
  auto isMoving = [&](std::uint16_t id) { return id != 0 && id < moving.size() && moving[id]; };
  // The moving instance at the pixel nearest p, else 0.
  auto movingIdAt = [&](cv::Point2f p) -> std::uint16_t {
    const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
    if (x < 0 || y < 0 || x >= instances.cols || y >= instances.rows) return 0;
    const std::uint16_t id = instances.at<std::uint16_t>(y, x);
    return isMoving(id) ? id : 0;
  };
  const bool geometry = !out.cluster_map.empty();
  const int clusters = static_cast<int>(out.cluster_scores.size());
  std::vector<int> cluster_px(clusters, 0);
  std::map<std::uint16_t, MoverFrameDiagnosis> per_id;
  std::map<std::uint16_t, std::vector<int>> overlap;
  for (int y = 0; y < instances.rows; ++y) {
    const std::uint16_t* id = instances.ptr<std::uint16_t>(y);
    const uchar* m = out.mask.ptr<uchar>(y);
    const int* c = geometry ? out.cluster_map.ptr<int>(y) : nullptr;
    for (int x = 0; x < instances.cols; ++x) {
      if (c && c[x] >= 0 && c[x] < clusters) ++cluster_px[c[x]];
      if (!isMoving(id[x])) continue;
      MoverFrameDiagnosis& d = per_id[id[x]];
      ++d.pixels;
      d.marked += m[x] != 0;
      if (c && c[x] >= 0 && c[x] < clusters) {
        std::vector<int>& o = overlap[id[x]];
        if (o.empty()) o.assign(clusters, 0);
        ++o[c[x]];
      }
    }
  }
  std::map<std::uint16_t, std::vector<double>> initial, judged;
  for (std::size_t i = 0; i < out.tracks.size(); ++i) {
    const std::uint16_t id = movingIdAt(out.tracks[i].current);
    if (id == 0) continue;
    MoverFrameDiagnosis& d = per_id[id];
    ++d.tracks;
    if (i < out.reprojection_error_px.size() && out.reprojection_error_px[i]) {
      ++d.tracks_scored;
      initial[id].push_back(*out.reprojection_error_px[i]);
    }
    if (i < out.judged_error_px.size() && out.judged_error_px[i]) judged[id].push_back(*out.judged_error_px[i]);
    if (i < out.epipolar_distance_px.size() && out.epipolar_distance_px[i] > options.epipolar.dynamic_threshold_px &&
        std::isfinite(out.epipolar_distance_px[i]))
      ++d.epipolar_violators;
  }
  std::map<std::uint16_t, std::vector<double>> over_baseline;
  for (const BaselinePoint& b : out.baseline_points) {
    const std::uint16_t id = movingIdAt(b.current);
    if (id == 0) continue;
    MoverFrameDiagnosis& d = per_id[id];
    ++d.baseline_points;
    d.baseline_moving += b.moving;
    over_baseline[id].push_back(b.residual_px);
  }
  std::vector<MoverFrameDiagnosis> result;
  for (auto& [id, d] : per_id) {
    d.id = id;
    d.median_initial_px = median(initial[id]);
    d.median_judged_px = median(judged[id]);
    d.median_baseline_px = median(over_baseline[id]);
    for (int c = 0; c < clusters && overlap.count(id); ++c) {
      if (overlap[id][c] == 0) continue;
      MoverClusterView v;
      v.cluster = c;
      v.overlap_px = overlap[id][c];
      v.cluster_px = cluster_px[c];
      v.tracks = out.cluster_scores[c].points;
      v.initial_px = out.cluster_scores[c].equivalent_px;
      v.candidate = out.cluster_scores[c].candidate;
      if (c < static_cast<int>(out.confirm_scores.size())) {
        v.confirm_px = out.confirm_scores[c].equivalent_px;
        v.confirmed = out.confirm_scores[c].candidate;
      }
      v.dynamic = c < static_cast<int>(out.dynamic_cluster.size()) && out.dynamic_cluster[c];
      d.clusters.push_back(v);
    }
    std::sort(d.clusters.begin(), d.clusters.end(),
              [](const MoverClusterView& a, const MoverClusterView& b) { return a.overlap_px > b.overlap_px; });
    // The first stage that lost it, judged on the clusters that hold at least a fifth of it.
    bool any_dynamic = false, any_candidate = false, any_pure = false;
    for (const MoverClusterView& v : d.clusters) {
      if (5 * v.overlap_px < d.pixels) continue;
      any_dynamic |= v.dynamic;
      any_candidate |= v.candidate || v.confirmed;
      any_pure |= 2 * v.overlap_px >= v.cluster_px;
    }
    if (2 * d.marked >= d.pixels)
      d.cause = "found";
    else if (d.tracks_scored < options.reprojection.min_points_per_cluster)
      d.cause = "no-tracks";
    else if (any_dynamic)
      d.cause = "mask";
    else if (any_candidate)
      d.cause = "no-decision";
    else if (!any_pure)
      d.cause = "mixed-cluster";
    else
      d.cause = "below-threshold";
    result.push_back(std::move(d));
  }
  return result;
}

}  // namespace amos::dynamic
