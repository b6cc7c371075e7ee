#pragma once
// Scoring a dense map against the truth of a synthetic sequence: its static surface (synth/static_surface.h) and
// the volume its movers swept (synth/swept_volume.h):
//   accuracy      distance of each reconstructed vertex to the nearest truth point: median and 90th percentile;
//   completeness  share of the truth points with a reconstructed vertex within `tolerance`;
//   ghosts        reconstructed vertices inside the movers' swept volume (grown by `sweep_margin`) and farther than
//                 `tolerance` from every truth point: remains of people and objects (issue 43's measure). The floor
//                 under a walker's feet is in the sweep but on the static surface: not a ghost;
//   off_surface   reconstructed vertices farther than `tolerance` from every truth point, wherever they are: the
//                 ghosts and the reconstruction's gross errors (smeared walls, surfaces the truth samples miss).
// Distances are to the nearest sample (1 cm cells), so they read up to ~5 mm high on a flat surface. The tolerance
// is 2 voxels by default (4 cm): a static vertex lies within a voxel of its surface plus the depth noise. The sweep
// is grown by the tolerance by default: a mover's reconstructed surface lies within the same band of its true one,
// which bounds the sweep.
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
#include "amos/synth/swept_volume.h"

namespace amos::eval {

struct MeshScore {
  std::size_t vertices = 0, truth_points = 0;
  std::size_t ghosts = 0;       // in the grown sweep and off the static surface
  std::size_t off_surface = 0;  // off the static surface, anywhere
  std::size_t in_sweep = 0;     // in the grown sweep, on the static surface or not
  double tolerance_m = 0.04, sweep_margin_m = 0.04;
  double accuracy_median_m = 0, accuracy_p90_m = 0;
  double completeness = 0, ghost_share = 0, off_surface_share = 0;  // shares of the vertices
  std::size_t swept_cells = 0;
  double swept_cell_m = 0, swept_volume_m3 = 0;
  double ate_rmse_m = 0;  // of the run's trajectory (ATE's own alignment), for reference
  std::vector<Eigen::Vector3d> ghost_points;  // the ghost vertices (ground truth frame), to look at; not in toJson
};

// T_gt_est: the rotation nearest to the mean of the associated pairs' R_gt R_est^T (chordal mean) and the mean
// translation that goes with it. Throws core::Error when no pose associates.
core::SE3 alignByPoses(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est);

MeshScore scoreMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3d>& truth,
                    const synth::SweptVolume& swept, double tolerance, double sweep_margin);

// The vertices of a mesh PLY. Throws core::Error naming the file when it cannot be read, and the first vertex that
// is not finite: such a file is damaged (a dense map never has one), and scoring the rest would hide it.
std::vector<Eigen::Vector3d> readMeshVertices(const std::string& path);

struct MeshEvalRequest {
  std::string mesh;        // mesh.ply (or any PLY with vertices) of a run
  std::string sequence;    // the synthetic sequence folder: static_surface.ply, swept_volume.ply, groundtruth.txt
  // The movers' swept volume ("" = swept_volume.ply of `sequence`). A static twin (rendered without movers) has an
  // empty one: give it its moving sibling's so that both maps are scored against the same volume.
  std::string swept;
  std::string trajectory;  // the run's trajectory.txt ("" = trajectory.txt beside the mesh)
  double tolerance = 0.04; // m
  double sweep_margin = -1;  // m, the sweep grown by this (< 0 = the tolerance)
  double max_depth = 4.0;  // truth points seen only from farther than this are left out (Dense.maxDepth)
};

// Throws core::Error naming the file that is missing or wrong (a sequence rendered before static_surface.ply or
// swept_volume.ply existed: render it again).
MeshScore evaluateMesh(const MeshEvalRequest& request);

nlohmann::json toJson(const MeshScore& score);

// Writes points as a PLY point cloud (eval-mesh --ghosts). Throws core::Error naming the file.
void writePointsPly(const std::string& path, const std::vector<Eigen::Vector3d>& points);

}  // namespace amos::eval
