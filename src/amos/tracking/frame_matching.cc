#include "amos/tracking/frame_matching.h"

#include <spdlog/spdlog.h>

#include "amos/match/brute_force_search.h"
#include "amos/match/pose_from_matches.h"
#include "amos/tracking/depth_order.h"
#include "amos/tracking/matching.h"

namespace amos::tracking {

void addTemporaryPoints(map::Frame& last, int min_points, std::vector<map::MapPointPtr>& temporaries) {
  const map::FrameFeatures& f = *last.features;
  const auto by_depth = keypointsByDepth(f, last.sensor->closeDepth(), min_points);
  int n = 0;
  for (const auto& [z, i] : by_depth) {
    const auto& p = last.map_points[i];
    if (!p || p->numObservations() < 1) {
      auto temp = std::make_shared<map::MapPoint>(map::kNoMapPoint, last.unproject(i), map::kNoKeyFrame, last.id);
      temp->setDescriptor(f.descriptors.row(i));
      last.map_points[i] = temp;
      last.outlier[i] = false;
      temporaries.push_back(std::move(temp));
    }
    ++n;
    if (z > last.sensor->closeDepth() && n > min_points) break;
  }
}

int discardOutliers(map::Frame& frame) {
  int in_map = 0;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    auto& p = frame.map_points[i];
    if (!p) continue;
    if (frame.outlier[i]) {
      p.reset();
      frame.outlier[i] = false;
    } else if (p->numObservations() > 0) {
      ++in_map;
    }
  }
  return in_map;
}

MotionModelMatch trackWithMotionModel(map::Frame& frame, const map::Frame& last,
                                      const std::vector<PosePrediction>& predictions, const TrackerOptions& options) {
  MotionModelMatch result;
  const double th = options.motion_search_radius;
  int best_n = -1;
  std::vector<map::MapPointPtr> best_matches;
  bool best_is_last = false;
  core::SE3 best_pose = core::SE3::Identity();
  for (const PosePrediction& prediction : predictions) {
    frame.resetMatches();
    frame.setPose(prediction.T_cw);
    int n = searchLastFrame(frame, last, th, options.matching);
    if (n < options.motion_min_matches) {
      frame.resetMatches();
      n = searchLastFrame(frame, last, 2 * th, options.matching);
    }
    best_is_last = n > best_n;
    if (best_is_last) {
      best_n = n;
      // Taken, not copied: the next prediction starts from resetMatches() anyway.
      best_matches.swap(frame.map_points);
      best_pose = prediction.T_cw;
      result.used_external = prediction.external;
    }
  }
  spdlog::debug("frame {}: motion model {} matches", frame.id, best_n);
  if (best_n < options.motion_min_matches) {
    if (best_is_last) frame.map_points.swap(best_matches);  // the frame keeps the last prediction's matches
    return result;
  }
  frame.map_points = std::move(best_matches);
  frame.outlier.assign(frame.size(), false);
  frame.setPose(best_pose);
  const int inl = match::optimizeFramePose(frame, options.pose);
  const int in_map = discardOutliers(frame);
  spdlog::debug("frame {}: motion model inliers {} (in map {}) prediction off by {:.4f} m {:.3f} deg", frame.id, inl,
                in_map, core::translationNorm(best_pose * frame.T_cw.inverse()),
                core::rotationAngle(best_pose * frame.T_cw.inverse()) * 57.3);
  result.tracked = in_map >= options.min_map_matches;
  return result;
}

bool trackReferenceKeyFrame(map::Frame& frame, const map::KeyFrame& reference, const core::SE3& T_prior,
                            const TrackerOptions& options) {
  int n = 0;
  auto matches =
      match::matchFrameToKeyFrame(frame, reference, options.matching.brute_force_ratio, options.matching, &n);
  spdlog::debug("frame {}: reference keyframe {} matches", frame.id, n);
  if (n < options.reference_min_matches) return false;
  frame.map_points = std::move(matches);
  frame.outlier.assign(frame.size(), false);
  frame.setPose(T_prior);
  match::optimizeFramePose(frame, options.pose);
  return discardOutliers(frame) >= options.min_map_matches;
}

}  // namespace amos::tracking
