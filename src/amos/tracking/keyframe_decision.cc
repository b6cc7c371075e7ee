#include "amos/tracking/keyframe_decision.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <vector>

namespace amos::tracking {

ClosePoints countClosePoints(const map::Frame& frame) {
  ClosePoints close;
  const map::FrameFeatures& f = *frame.features;
  const double close_depth = frame.sensor->closeDepth();
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.depth[i] > 0 && f.depth[i] < close_depth) {
      if (frame.map_points[i] && !frame.outlier[i]) {
        ++close.tracked;
      } else {
        ++close.untracked;
      }
    }
  }
  return close;
}

std::optional<ViewChange> viewChange(const map::Frame& frame, const core::SE3& T_rw) {
  std::vector<float> depths;
  const map::FrameFeatures& f = *frame.features;
  depths.reserve(f.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.depth[i] > 0) depths.push_back(f.depth[i]);
  if (depths.empty()) return std::nullopt;
  const auto mid = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
  std::nth_element(depths.begin(), mid, depths.end());
  // T_cr = T_cw * T_wr: its rotation is the turn between the two views, its translation (in the camera frame) the
  // baseline between the two camera centres.
  const core::SE3 T_cr = frame.T_cw * T_rw.inverse();
  const double kDegree = 3.14159265358979323846 / 180.0;
  return ViewChange{core::rotationAngle(T_cr) / kDegree, core::translationNorm(T_cr) / static_cast<double>(*mid)};
}

bool settlingAfterRelocalisation(const KeyFrameEvidence& e, const TrackerOptions& o) {
  const auto max_frames = static_cast<map::FrameId>(o.max_frames_between_keyframes);
  return e.last_relocalization && e.frame < *e.last_relocalization + max_frames &&
         e.keyframes_in_map > o.max_frames_between_keyframes;
}

bool lacksClosePoints(const KeyFrameEvidence& e, const TrackerOptions& o) {
  return e.close.tracked < o.close_tracked_max && e.close.untracked > o.close_untracked_min;
}

bool losingReferencePoints(const KeyFrameEvidence& e, const TrackerOptions& o) {
  const double ref_ratio = e.keyframes_in_map < 2 ? 0.4 : o.keyframe_ref_ratio;
  return (e.inliers < e.reference_tracked * ref_ratio || lacksClosePoints(e, o)) && e.inliers > 15;
}

bool viewMovedOn(const std::optional<ViewChange>& view, const TrackerOptions& o) {
  return view && ((o.keyframe_view_rotation_deg > 0 && view->rotation_deg >= o.keyframe_view_rotation_deg) ||
                  (o.keyframe_view_baseline > 0 && view->baseline_share >= o.keyframe_view_baseline));
}

bool keyFrameDue(const KeyFrameEvidence& e, const std::optional<ViewChange>& view, const TrackerOptions& o) {
  const bool max_frames_passed =
      e.frame >= e.last_keyframe_frame + static_cast<map::FrameId>(o.max_frames_between_keyframes);
  const bool min_frames_passed_idle =
      e.frame >= e.last_keyframe_frame + static_cast<map::FrameId>(o.min_frames_between_keyframes) && e.mapping_idle;
  const bool weak = e.inliers < e.reference_tracked * 0.25 || lacksClosePoints(e, o);
  return max_frames_passed || min_frames_passed_idle || weak || viewMovedOn(view, o);
}

bool trackingSound(const KeyFrameEvidence& e, const TrackerOptions& o) {
  return e.inliers >= e.reference_tracked * 0.25 && e.inliers >= o.close_tracked_max;
}

bool stillBehindMovers(const cv::Mat& dynamic_mask, const std::optional<ViewChange>& view, const TrackerOptions& o) {
  if (!view || o.keyframe_min_rotation_deg <= 0 || o.keyframe_min_baseline <= 0 || o.keyframe_mover_share <= 0 ||
      dynamic_mask.empty())
    return false;
  if (cv::countNonZero(dynamic_mask) < o.keyframe_mover_share * static_cast<double>(dynamic_mask.total())) return false;
  return view->rotation_deg < o.keyframe_min_rotation_deg && view->baseline_share < o.keyframe_min_baseline;
}

bool wantsKeyFrame(const KeyFrameEvidence& e, const map::Frame& frame, const std::optional<core::SE3>& T_rw,
                   const TrackerOptions& o) {
  if (settlingAfterRelocalisation(e, o)) return false;
  spdlog::debug("frame {}: keyframe test: inliers {} reference tracked {} close tracked {} untracked {}{}", e.frame,
                e.inliers, e.reference_tracked, e.close.tracked, e.close.untracked,
                e.mapping_idle ? "" : " mapping busy");
  if (!losingReferencePoints(e, o)) return false;
  // How far the camera is from the reference keyframe's viewpoint, measured once for both view rules.
  const std::optional<ViewChange> view = T_rw ? viewChange(frame, *T_rw) : std::nullopt;
  if (!keyFrameDue(e, view, o)) return false;
  if (trackingSound(e, o) && stillBehindMovers(frame.dynamic_mask, view, o)) {
    spdlog::debug(
        "frame {}: no keyframe: movers hide part of the view, the camera is still at the reference "
        "keyframe's viewpoint",
        e.frame);
    return false;
  }
  return true;
}

}  // namespace amos::tracking
