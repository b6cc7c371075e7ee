#pragma once
// EPnP (Lepetit, Moreno-Noguer and Fua, "EPnP: An Accurate O(n) Solution to the PnP Problem", IJCV 2009):
// camera pose from n >= 4 world points and their normalised image coordinates, in closed form. The points are
// written as weighted sums of four control points whose camera coordinates span the null space of a 2n x 12
// system; the null-space weights come from preserving the control points' mutual distances (three
// approximations, each polished by Gauss-Newton, the best by reprojection error wins).
#include <Eigen/Core>

#include <optional>
#include <vector>

#include "amos/core/pose.h"

namespace amos::geometry {

// normalized[i] = (x / z, y / z) of points_w[i] in the camera, i.e. ((u - cx) / fx, (v - cy) / fy) for an
// undistorted pixel. Returns T_cw, or nothing when the configuration is degenerate (fewer than 4 points,
// collinear points, non-finite result). For nearly coplanar point sets (the common case of a wall), where the
// four-control-point form is ill-posed, OpenCV's SQPnP is tried as well and the lower reprojection error wins.
std::optional<core::SE3> solveEpnp(const std::vector<Eigen::Vector3d>& points_w,
                                   const std::vector<Eigen::Vector2d>& normalized);

}  // namespace amos::geometry
