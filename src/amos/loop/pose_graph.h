#pragma once
// SE(3) pose-graph optimisation with Ceres, as a pure function of plain data (testable without a map).
// Vertices are world-to-camera poses T_iw; an edge (i, j) holds the measured relative pose T_ij = T_iw * T_jw^-1
// (camera j expressed in camera i). The residual of an edge is the 6-vector [2 vec(q_err) rotation_scale, t_err]
// of T_ij_measured^-1 * T_iw * T_jw^-1, times the edge's weight.
#include <vector>

#include "amos/core/pose.h"

namespace amos::loop {

struct PoseGraphEdge {
  int i = 0, j = 0;
  core::SE3 T_ij = core::SE3::Identity();
  double weight = 1.0;
  // Metres per radian of the rotation residual: an angular error moves the scene by about angle x distance,
  // so with the scene's typical depth here both parts of the residual are displacements in metres. With 1 a
  // pose graph absorbs translation drift by bending the whole loop (rotation is "cheap").
  double rotation_scale = 1.0;
};

struct PoseGraphOptions {
  int max_iterations = 20;  // Loop.poseGraphIterations (ORB-SLAM2 optimises the essential graph for 20)
  void check() const;
};

struct PoseGraphResult {
  std::vector<core::SE3> T_iw;
  double initial_cost = 0, final_cost = 0;
  int iterations = 0;
};

// `fixed[i]` keeps vertex i where it is (at least one vertex must be fixed: the gauge).
PoseGraphResult optimizePoseGraph(const std::vector<core::SE3>& T_iw, const std::vector<bool>& fixed,
                                  const std::vector<PoseGraphEdge>& edges, const PoseGraphOptions& options);

}  // namespace amos::loop
