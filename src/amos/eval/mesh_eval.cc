#include "amos/eval/mesh_eval.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <cmath>
#include <filesystem>

#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/PointCloudIO.h>
#include <open3d/io/TriangleMeshIO.h>

#include "amos/core/error.h"
#include "amos/core/stage_timer.h"
#include "amos/eval/associate.h"
#include "amos/eval/evaluate.h"
#include "amos/io/trajectory.h"
#include "amos/synth/static_surface.h"

namespace amos::eval {

namespace fs = std::filesystem;

namespace {

// Distance from each of `queries` to its nearest point of `points`.
std::vector<double> nearestDistances(const std::vector<Eigen::Vector3d>& queries,
                                     const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> out(queries.size(), std::numeric_limits<double>::infinity());
  if (points.empty()) return out;
  open3d::geometry::PointCloud cloud(points);
  const open3d::geometry::KDTreeFlann tree(cloud);
  std::vector<int> index;
  std::vector<double> squared;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    if (tree.SearchKNN(queries[i], 1, index, squared) > 0) out[i] = std::sqrt(squared[0]);
  }
  return out;
}

}  // namespace

core::SE3 alignByPoses(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est) {
  const auto g = sortedUniqueByTimestamp(gt), e = sortedUniqueByTimestamp(est);
  const auto pairs = associate(timestampsOf(g), timestampsOf(e));
  core::require(!pairs.empty(), "eval-mesh: no pose of the trajectory has a ground-truth pose at its time stamp");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const auto& [i, j] : pairs) sum += g[i].T_wc.linear() * e[j].T_wc.linear().transpose();
  // The rotation nearest (Frobenius) to the mean of the per-pose rotations (chordal mean).
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) {
    Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
    flip(2, 2) = -1;
    R = svd.matrixU() * flip * svd.matrixV().transpose();
  }
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (const auto& [i, j] : pairs) t += g[i].T_wc.translation() - R * e[j].T_wc.translation();
  core::SE3 T = core::SE3::Identity();
  T.linear() = R;
  T.translation() = t / static_cast<double>(pairs.size());
  return T;
}

MeshScore scoreMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3d>& truth,
                    const synth::SweptVolume& swept, double tolerance, double sweep_margin) {
  MeshScore score;
  score.vertices = vertices.size();
  score.truth_points = truth.size();
  score.tolerance_m = tolerance;
  score.sweep_margin_m = sweep_margin;
  score.swept_cells = swept.size();
  score.swept_cell_m = swept.cell();
  score.swept_volume_m3 = swept.volumeM3();
  const std::vector<double> to_truth = nearestDistances(vertices, truth);
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const bool off = to_truth[i] > tolerance;
    const bool in_sweep = std::isfinite(swept.distanceTo(vertices[i], sweep_margin));
    score.off_surface += off ? 1 : 0;
    score.in_sweep += in_sweep ? 1 : 0;
    if (off && in_sweep) {
      ++score.ghosts;
      score.ghost_points.push_back(vertices[i]);
    }
  }
  if (!to_truth.empty()) {
    score.accuracy_median_m = core::percentile(to_truth, 0.5);
    score.accuracy_p90_m = core::percentile(to_truth, 0.9);
    const double n = static_cast<double>(to_truth.size());
    score.ghost_share = static_cast<double>(score.ghosts) / n;
    score.off_surface_share = static_cast<double>(score.off_surface) / n;
  }
  const std::vector<double> to_mesh = nearestDistances(truth, vertices);
  std::size_t covered = 0;
  for (double d : to_mesh) covered += d <= tolerance ? 1 : 0;
  if (!truth.empty()) score.completeness = static_cast<double>(covered) / static_cast<double>(truth.size());
  return score;
}

std::vector<Eigen::Vector3d> readMeshVertices(const std::string& path) {
  open3d::geometry::TriangleMesh mesh;
  core::require(fs::exists(path) && open3d::io::ReadTriangleMesh(path, mesh),
                fmt::format("{}: cannot be read as a mesh", path));
  for (std::size_t i = 0; i < mesh.vertices_.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices_[i];
    core::require(v.allFinite(), fmt::format("{}: vertex {} of {} is not finite ({}, {}, {}): the mesh is damaged, "
                                             "nothing is scored",
                                             path, i, mesh.vertices_.size(), v.x(), v.y(), v.z()));
  }
  return std::move(mesh.vertices_);
}

MeshScore evaluateMesh(const MeshEvalRequest& request) {
  const fs::path surface = fs::path(request.sequence) / synth::kStaticSurfaceFile;
  core::require(fs::exists(surface),
                fmt::format("{} is missing: render the sequence again with `amos-slam synth` (it writes the true "
                            "static surface since issue 43)",
                            surface.string()));
  const fs::path swept_file =
      request.swept.empty() ? fs::path(request.sequence) / synth::kSweptVolumeFile : fs::path(request.swept);
  core::require(fs::exists(swept_file),
                request.swept.empty()
                    ? fmt::format("{} is missing: render the sequence again with `amos-slam synth` (it writes the "
                                  "movers' swept volume since issue 43), or give one with --swept",
                                  swept_file.string())
                    : fmt::format("{}: no such swept volume file", swept_file.string()));
  const synth::SweptVolume swept = synth::readSweptVolumePly(swept_file.string());
  std::vector<Eigen::Vector3d> truth;
  for (const synth::SurfaceSample& s : synth::readSurfacePly(surface.string())) {
    if (s.depth <= request.max_depth) truth.push_back(s.position.cast<double>());
  }
  const std::vector<Eigen::Vector3d> mesh = readMeshVertices(request.mesh);
  const std::string trajectory_file = request.trajectory.empty()
                                          ? (fs::path(request.mesh).parent_path() / "trajectory.txt").string()
                                          : request.trajectory;
  const auto gt = io::readTumTrajectory((fs::path(request.sequence) / "groundtruth.txt").string());
  const auto est = io::readTumTrajectory(trajectory_file);
  const core::SE3 T_gt_est = alignByPoses(gt, est);
  std::vector<Eigen::Vector3d> vertices;
  vertices.reserve(mesh.size());
  for (const auto& v : mesh) vertices.push_back(T_gt_est * v);
  const double margin = request.sweep_margin < 0 ? request.tolerance : request.sweep_margin;
  MeshScore score = scoreMesh(vertices, truth, swept, request.tolerance, margin);
  score.ate_rmse_m = evaluate(gt, est).ate_rmse_m;
  return score;
}

nlohmann::json toJson(const MeshScore& s) {
  return {{"vertices", s.vertices},
          {"truth_points", s.truth_points},
          {"tolerance_m", s.tolerance_m},
          {"accuracy_median_m", s.accuracy_median_m},
          {"accuracy_p90_m", s.accuracy_p90_m},
          {"completeness", s.completeness},
          {"ghosts", s.ghosts},
          {"ghost_share", s.ghost_share},
          {"off_surface", s.off_surface},
          {"off_surface_share", s.off_surface_share},
          {"in_sweep", s.in_sweep},
          {"sweep_margin_m", s.sweep_margin_m},
          {"swept_cells", s.swept_cells},
          {"swept_cell_m", s.swept_cell_m},
          {"swept_volume_m3", s.swept_volume_m3},
          {"ate_rmse_m", s.ate_rmse_m}};
}

void writePointsPly(const std::string& path, const std::vector<Eigen::Vector3d>& points) {
  const open3d::geometry::PointCloud cloud(points);
  core::require(open3d::io::WritePointCloudToPLY(path, cloud, {}), fmt::format("cannot write {}", path));
}

}  // namespace amos::eval
