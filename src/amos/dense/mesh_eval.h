#pragma once
// Scoring a dense map against the true static surface of a synthetic sequence (synth/static_surface.h):
//   accuracy      distance of each reconstructed vertex to the nearest truth point: median and 90th percentile;
//   completeness  share of the truth points with a reconstructed vertex within `tolerance`;
//   ghosts        reconstructed vertices farther than `tolerance` from every truth point (count and share): what
//                 the map holds that the static world has not, i.e. movers smeared into it (and gross errors).
// Distances are to the nearest sample (1 cm cells), so they read up to ~5 mm high on a flat surface. The tolerance
// is 2 voxels by default (4 cm): a static vertex lies within a voxel of its surface plus the depth noise.
// The map is in the run's world frame; it is moved onto the ground truth's by the rigid transform that best maps
// the run's camera poses onto the ground truth's (alignByPoses), so trajectory errors count too. Not ATE's
// alignment of positions alone: for a still camera (walking_static) or a short sideways path its rotation is
// undetermined, and a degree of rotation moves a wall 4 m away by 7 cm.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "amos/core/pose.h"
#include "amos/io/trajectory.h"

namespace amos::dense {

struct MeshScore {
  std::size_t vertices = 0, truth_points = 0, ghosts = 0;
  double tolerance_m = 0.04;
  double accuracy_median_m = 0, accuracy_p90_m = 0;
  double completeness = 0, ghost_share = 0;
  double ate_rmse_m = 0;  // of the run's trajectory (ATE's own alignment), for reference
};

// T_gt_est: the rotation nearest to the mean of the associated pairs' R_gt R_est^T (chordal mean) and the mean
// translation that goes with it. Throws core::Error when no pose associates.
core::SE3 alignByPoses(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est);

MeshScore scoreMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3d>& truth,
                    double tolerance);

struct MeshEvalRequest {
  std::string mesh;        // mesh.ply (or any PLY with vertices) of a run
  std::string sequence;    // the synthetic sequence folder: static_surface.ply, groundtruth.txt
  std::string trajectory;  // the run's trajectory.txt ("" = trajectory.txt beside the mesh)
  double tolerance = 0.04; // m
  double max_depth = 4.0;  // truth points seen only from farther than this are left out (Dense.maxDepth)
};

// Throws core::Error naming the file that is missing or wrong (a sequence rendered before static_surface.ply
// existed: render it again).
MeshScore evaluateMesh(const MeshEvalRequest& request);

nlohmann::json toJson(const MeshScore& score);

}  // namespace amos::dense
