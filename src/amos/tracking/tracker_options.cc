#include "amos/tracking/tracker_options.h"

#include <fmt/format.h>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::tracking {

void TrackerOptions::check() const {
  core::requireAtLeast(init_min_depth_points, "init_min_depth_points", 10);
  core::requirePositive(motion_search_radius, "motion_search_radius");
  core::requireAtLeast(motion_min_matches, "motion_min_matches", 6);
  core::requireAtLeast(min_map_matches, "min_map_matches", 3);
  core::requireAtLeast(reference_min_matches, "reference_min_matches", 6);
  core::requirePositive(local_search_radius, "local_search_radius");
  core::requirePositive(reloc_search_radius, "reloc_search_radius");
  core::requireAtLeast(local_min_inliers, "local_min_inliers", 6);
  core::requireOption(reloc_min_inliers >= local_min_inliers, core::option(reloc_min_inliers, "reloc_min_inliers"),
                      fmt::format("must be >= local_min_inliers = {}, got {}", local_min_inliers, reloc_min_inliers),
                      {core::option(local_min_inliers, "local_min_inliers")});
  core::requireAtLeast(max_local_keyframes, "max_local_keyframes", 1);
  core::requireAtLeast(max_frames_between_keyframes, "max_frames_between_keyframes", 1);
  core::requireOption(min_frames_between_keyframes >= 0 && min_frames_between_keyframes <= max_frames_between_keyframes,
                      core::option(min_frames_between_keyframes, "min_frames_between_keyframes"),
                      fmt::format("must be in [0, max_frames_between_keyframes = {}], got {}",
                                  max_frames_between_keyframes, min_frames_between_keyframes),
                      {core::option(max_frames_between_keyframes, "max_frames_between_keyframes")});
  core::requireOption(keyframe_ref_ratio > 0 && keyframe_ref_ratio <= 1,
                      core::option(keyframe_ref_ratio, "keyframe_ref_ratio"),
                      fmt::format("must be in (0, 1], got {}", keyframe_ref_ratio));
  core::requireInRange(keyframe_min_rotation_deg, "keyframe_min_rotation_deg", 0.0, 90.0);
  core::requireInRange(keyframe_min_baseline, "keyframe_min_baseline", 0.0, 1.0);
  core::requireInRange(keyframe_mover_share, "keyframe_mover_share", 0.0, 1.0);
  core::requireInRange(keyframe_view_rotation_deg, "keyframe_view_rotation_deg", 0.0, 180.0);
  core::requireInRange(keyframe_view_baseline, "keyframe_view_baseline", 0.0, 10.0);
  core::requireAtLeast(close_tracked_max, "close_tracked_max", 0);
  core::requireAtLeast(close_untracked_min, "close_untracked_min", 0);
  core::requireAtLeast(new_points_min, "new_points_min", 0);
  core::requireAtLeast(vo_points_min, "vo_points_min", 0);
  core::requireAtLeast(recovery_frames, "recovery_frames", 0);
  core::requirePositive(recovery_search_radius, "recovery_search_radius");
  pose.check();
  matching.check();
  relocalization.check();
}

}  // namespace amos::tracking
