#pragma once
// Two-view linear (DLT) triangulation of a point from normalised image coordinates, as used by local mapping to
// create map points between neighbouring keyframes.
#include <Eigen/Core>
#include <optional>

#include "amos/core/pose.h"

namespace amos::geometry {

// x1, x2: normalised coordinates ((u - cx) / fx, (v - cy) / fy) of the same point seen from cameras with poses
// T_c1w and T_c2w. Returns the world point, or nullopt when the solution is at infinity / not finite.
std::optional<Eigen::Vector3d> triangulateDlt(const Eigen::Vector2d& x1, const core::SE3& T_c1w,
                                              const Eigen::Vector2d& x2, const core::SE3& T_c2w);

}  // namespace amos::geometry
