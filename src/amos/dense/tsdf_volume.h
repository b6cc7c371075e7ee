#pragma once
// The TSDF volume: Open3D's ScalableTSDFVolume (voxel blocks allocated where depth lands, marching cubes) behind
// this project's types (core::SE3, cv::Mat). Not thread-safe: one thread integrates and extracts.
//
// Threads: Open3D's loops are OpenMP loops sized to every core, whose waiting threads spin; beside tracking on a
// loaded machine that spinning cost the integration 3 to 10 times its CPU time (measured: 25 ms of work became
// 115 ms). serialOpenMpInThisThread() makes every OpenMP region the calling thread starts run on that thread
// alone (max-active-levels 0 is a per-thread setting): the live fusion thread calls it; the final fusion after
// the run uses every core.
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "amos/core/camera.h"
#include "amos/core/pose.h"
#include "amos/dense/dense_options.h"

namespace open3d::geometry {
class PointCloud;
class TriangleMesh;
}  // namespace open3d::geometry
namespace open3d::pipelines::integration {
class ScalableTSDFVolume;
}  // namespace open3d::pipelines::integration

namespace amos::dense {

void serialOpenMpInThisThread();

class TsdfVolume {
 public:
  explicit TsdfVolume(const DenseOptions& options);
  ~TsdfVolume();
  TsdfVolume(const TsdfVolume&) = delete;
  TsdfVolume& operator=(const TsdfVolume&) = delete;

  // depth: CV_32F metres (0 = not fused), bgr: CV_8UC3, both of `camera`'s size (no distortion).
  void integrate(const cv::Mat& depth, const cv::Mat& bgr, const core::CameraIntrinsics& camera,
                 const core::SE3& T_cw);
  // Marching cubes: vertices with colours (and normals), in the world frame of the poses.
  std::shared_ptr<open3d::geometry::TriangleMesh> extractMesh() const;
  // The surface's points (zero crossings of the TSDF) with colours and normals.
  std::shared_ptr<open3d::geometry::PointCloud> extractCloud() const;

  // Free-space carving (free_space_carving.h): forgets the voxels under each of `vertices`, points that
  // extractMesh() or extractCloud() gave (each lies on the edge between two voxel centres; both lose their weight,
  // so every cube of marching cubes that shares the edge, the vertex with its triangles and the cloud's point are
  // gone from the next extraction).
  // Returns the number of voxels forgotten.
  std::size_t forgetSurfaceAt(const std::vector<Eigen::Vector3d>& vertices);

  std::size_t blocks() const;       // allocated voxel blocks
  std::size_t voxels() const;       // blocks x voxels per block
  std::size_t bytes() const;        // memory of the voxels
  std::size_t integrated() const { return integrated_; }

 private:
  std::unique_ptr<open3d::pipelines::integration::ScalableTSDFVolume> volume_;
  double max_depth_;
  std::size_t integrated_ = 0;
};

}  // namespace amos::dense
