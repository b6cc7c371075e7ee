#include "amos/dense/free_space_carving.h"

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

#include "amos/dense/tsdf_volume.h"

namespace amos::dense {

SeeThroughOptions seeThroughOptionsOf(const DenseOptions& options) {
  SeeThroughOptions out;
  out.truncation = options.truncation;
  out.sigmas = options.carve_sigmas;
  out.min_depth = options.min_depth;
  out.max_depth = options.max_depth;
  out.min_votes = options.carve_min_votes;
  out.recent_votes = options.carve_recent_votes;
  return out;
}

FreeSpaceCarver FreeSpaceCarver::ofSurface(const TsdfVolume& volume, const SeeThroughOptions& options) {
  const auto mesh = volume.extractMesh();
  const auto cloud = volume.extractCloud();
  std::vector<Eigen::Vector3d> points = std::move(mesh->vertices_), colours = std::move(mesh->vertex_colors_);
  colours.resize(points.size(), Eigen::Vector3d(0.5, 0.5, 0.5));
  points.insert(points.end(), cloud->points_.begin(), cloud->points_.end());
  colours.insert(colours.end(), cloud->colors_.begin(), cloud->colors_.end());
  colours.resize(points.size(), Eigen::Vector3d(0.5, 0.5, 0.5));
  return FreeSpaceCarver(std::move(points), std::move(colours), options);
}

FreeSpaceCarver::FreeSpaceCarver(std::vector<Eigen::Vector3d> vertices, std::vector<Eigen::Vector3d> colours,
                                 const SeeThroughOptions& options)
    : colours_(std::move(colours)), vote_(std::move(vertices), options) {}

void FreeSpaceCarver::addFrame(const cv::Mat& depth, const core::CameraIntrinsics& camera, const core::SE3& T_cw) {
  vote_.addFrame(depth, camera, T_cw);
}

CarveResult FreeSpaceCarver::carve(TsdfVolume& volume) const {
  CarveResult out;
  out.vertices_voted = vote_.size();
  out.frames = vote_.frames();
  for (const std::size_t i : vote_.seenThroughIndices()) {
    out.points.push_back(vote_.point(i));
    out.colours.push_back(colours_[i]);
  }
  out.voxels_forgotten = volume.forgetSurfaceAt(out.points);
  return out;
}

}  // namespace amos::dense
