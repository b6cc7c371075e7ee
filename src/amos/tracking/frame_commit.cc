#include "amos/tracking/frame_commit.h"

#include "amos/map/map_point.h"

namespace amos::tracking {

std::optional<core::SE3> nextVelocity(const std::optional<core::SE3>& velocity, const MotionStep& step) {
  if (step.tracked && step.last_tracked && !step.relocalized) {
    return map::orthonormalized(step.T_cw * step.last_T_cw.inverse());
  }
  if (!step.tracked || step.relocalized) return std::nullopt;
  return velocity;
}

void dropTemporaryMatches(map::Frame& frame) {
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const auto& p = frame.map_points[i];
    if (p && p->numObservations() < 1) {
      frame.map_points[i].reset();
      frame.outlier[i] = false;
    }
  }
}

void dropOutlierMatches(map::Frame& frame) {
  for (std::size_t i = 0; i < frame.size(); ++i) {
    if (frame.map_points[i] && frame.outlier[i]) frame.map_points[i].reset();
    frame.outlier[i] = false;
  }
}

core::SE3 anchorToReference(map::Frame& frame, const ReferenceAnchoring& anchoring, const map::Map& map) {
  if (anchoring.tracked) {
    frame.reference_kf = anchoring.reference_kf;
    // The frame is its own keyframe: it follows every later correction of that keyframe (in lock-step mode local
    // mapping has already adjusted it by now).
    if (anchoring.own_keyframe) return core::SE3::Identity();
    return map::orthonormalized(frame.T_cw * map.keyFramePose(frame.reference_kf).inverse());
  }
  frame.reference_kf = anchoring.last_reference_kf;
  if (frame.reference_kf != map::kNoKeyFrame) frame.T_cw = anchoring.last_T_cr * map.keyFramePose(frame.reference_kf);
  return anchoring.last_T_cr;
}

}  // namespace amos::tracking
