#pragma once
// Free-space carving of the final volume (issue 55): after every kept frame is fused with its final pose, the
// surface's points (mesh vertices and cloud points) are voted on by every frame again (see_through.h: the static readings only, the dynamic mask and
// depth edges left out as in the fusion) and the points seen through lose the two voxels of their edge
// (TsdfVolume::forgetSurfaceAt): the surface that was there once and is free space now is gone from the mesh, the
// surface cloud and the floor plan made from it, and is added to the removed points.
//
// Why our own and not Open3D's: the legacy ScalableTSDFVolume has no ray-carving pass (voxblox and ReFusion clear
// space along each ray; Open3D clears only the voxels of the blocks a frame's depth lands in, which spares a ghost
// 16 cm or more in front of the wall behind it), while its blocks' voxels are public data, so a vote on the mesh's
// vertices and clearing their voxels is a few lines. Voting on the vertices, not every voxel, costs a projection per
// vertex and frame (70k vertices x 270 frames on the Bonn slice) and tests the surface itself: a voxel beside a wall
// at a grazing angle lies in free space by the TSDF's own account and must not carve the wall.
//
//   auto carver = FreeSpaceCarver::ofSurface(volume, seeThroughOptionsOf(options));
//   for (frame : kept frames) carver.addFrame(frame.depth, camera, T_cw);   // final poses
//   CarveResult carved = carver.carve(volume);
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dense/dense_options.h"
#include "amos/dense/see_through.h"

namespace amos::dense {

class TsdfVolume;

SeeThroughOptions seeThroughOptionsOf(const DenseOptions& options);

struct CarveResult {
  std::vector<Eigen::Vector3d> points, colours;  // the carved vertices with their colours (0-1)
  std::size_t vertices_voted = 0, voxels_forgotten = 0, frames = 0;
};

class FreeSpaceCarver {
 public:
  // The volume's current mesh vertices and surface cloud points (with their colours) are the points voted on: the
  // cloud has points where marching cubes has no vertex (zero crossings beside voxels never seen, at a
  // silhouette), and the floor plan is made from the cloud.
  static FreeSpaceCarver ofSurface(const TsdfVolume& volume, const SeeThroughOptions& options);
  FreeSpaceCarver(std::vector<Eigen::Vector3d> vertices, std::vector<Eigen::Vector3d> colours,
                  const SeeThroughOptions& options);
  void addFrame(const cv::Mat& depth, const core::CameraIntrinsics& camera, const core::SE3& T_cw);
  // Forgets the voxels under the vertices seen through.
  CarveResult carve(TsdfVolume& volume) const;

 private:
  std::vector<Eigen::Vector3d> colours_;
  SeeThroughVote vote_;
};

}  // namespace amos::dense
