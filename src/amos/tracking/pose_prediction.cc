#include "amos/tracking/pose_prediction.h"

#include "amos/map/frame.h"

namespace amos::tracking {

std::vector<PosePrediction> motionModelPredictions(const MotionHistory& history,
                                                   const std::optional<core::SE3>& external,
                                                   ExternalPosePolicy policy) {
  std::vector<PosePrediction> predictions;
  if (external) predictions.push_back({*external, true});
  if (history.velocity && !(external && policy == ExternalPosePolicy::kReplace)) {
    predictions.push_back({*history.velocity * history.last_T_cw, false});
  }
  if (predictions.empty() && history.last_tracked) predictions.push_back({history.last_T_cw, false});
  return predictions;
}

std::vector<core::SE3> recoveryPredictions(const LastTrackedPose& last, map::FrameId frame,
                                           const std::optional<core::SE3>& external) {
  std::vector<core::SE3> predictions;
  if (external) predictions.push_back(*external);
  // ORB-SLAM3 predicts the same way while recently lost (with an IMU).
  if (last.velocity && frame > last.frame) {
    core::SE3 T = last.T_cw;
    for (map::FrameId k = last.frame; k < frame; ++k) T = *last.velocity * T;
    predictions.push_back(map::orthonormalized(T));
  }
  predictions.push_back(last.T_cw);
  return predictions;
}

}  // namespace amos::tracking
