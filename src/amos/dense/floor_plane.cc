#include "amos/dense/floor_plane.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace amos::dense {

namespace {

struct Plane {
  Eigen::Vector3d normal;
  double offset = 0;
  std::vector<std::size_t> inliers;
};

// One point per cell (the first in the points' order: deterministic).
std::vector<Eigen::Vector3d> thinned(const std::vector<Eigen::Vector3d>& points, double cell) {
  std::map<std::tuple<long, long, long>, Eigen::Vector3d> cells;
  for (const auto& p : points) {
    const auto key = std::make_tuple(std::lround(std::floor(p.x() / cell)), std::lround(std::floor(p.y() / cell)),
                                     std::lround(std::floor(p.z() / cell)));
    cells.emplace(key, p);
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(cells.size());
  for (const auto& [key, p] : cells) out.push_back(p);
  return out;
}

std::vector<std::size_t> inliersOf(const std::vector<Eigen::Vector3d>& points, const std::vector<std::size_t>& among,
                                   const Eigen::Vector3d& normal, double offset, double distance) {
  std::vector<std::size_t> out;
  for (std::size_t i : among) {
    if (std::abs(normal.dot(points[i]) + offset) <= distance) out.push_back(i);
  }
  return out;
}

// The plane with the most inliers among `among`, refined by a least-squares fit to its inliers.
Plane largestPlane(const std::vector<Eigen::Vector3d>& points, const std::vector<std::size_t>& among,
                   const FloorSearch& search, std::mt19937& random) {
  Plane best;
  std::uniform_int_distribution<std::size_t> pick(0, among.size() - 1);
  for (int it = 0; it < search.iterations; ++it) {
    const Eigen::Vector3d a = points[among[pick(random)]], b = points[among[pick(random)]],
                          c = points[among[pick(random)]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9) continue;
    n.normalize();
    std::vector<std::size_t> inliers = inliersOf(points, among, n, -n.dot(a), search.inlier_distance);
    if (inliers.size() > best.inliers.size()) best = {n, -n.dot(a), std::move(inliers)};
  }
  if (best.inliers.size() < 3) return best;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i : best.inliers) mean += points[i];
  mean /= static_cast<double>(best.inliers.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i : best.inliers) scatter += (points[i] - mean) * (points[i] - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  Eigen::Vector3d n = solver.eigenvectors().col(0);  // smallest eigenvalue: the plane's normal
  if (n.dot(best.normal) < 0) n = -n;
  best.normal = n;
  best.offset = -n.dot(mean);
  best.inliers = inliersOf(points, among, best.normal, best.offset, search.inlier_distance);
  return best;
}

}  // namespace

std::optional<FloorPlane> findFloor(const std::vector<Eigen::Vector3d>& all_points,
                                    const std::vector<Eigen::Vector3d>& camera_centres,
                                    const std::vector<Eigen::Vector3d>& camera_down_axes,
                                    const FloorSearch& search) {
  if (camera_centres.empty() || camera_down_axes.empty()) return std::nullopt;
  Eigen::Vector3d down = Eigen::Vector3d::Zero();
  for (const auto& d : camera_down_axes) down += d;
  if (down.norm() < 1e-9) return std::nullopt;
  const Eigen::Vector3d up = -down.normalized();
  const std::vector<Eigen::Vector3d> points = thinned(all_points, search.thinning_cell);
  std::vector<std::size_t> rest(points.size());
  for (std::size_t i = 0; i < rest.size(); ++i) rest[i] = i;
  const std::size_t small = std::max<std::size_t>(50, points.size() / 20);
  std::mt19937 random(search.seed);
  std::vector<FloorPlane> candidates;
  for (int k = 0; k < search.max_planes && rest.size() >= small; ++k) {
    const Plane plane = largestPlane(points, rest, search, random);
    if (plane.inliers.size() < small) break;
    std::vector<std::size_t> left;
    std::set_difference(rest.begin(), rest.end(), plane.inliers.begin(), plane.inliers.end(), std::back_inserter(left));
    rest = std::move(left);
    FloorPlane floor{plane.normal.dot(up) >= 0 ? plane.normal : Eigen::Vector3d(-plane.normal), 0, plane.inliers.size()};
    floor.offset = plane.normal.dot(up) >= 0 ? plane.offset : -plane.offset;
    if (floor.normal.dot(up) < std::cos(search.max_tilt_deg * M_PI / 180.0)) continue;
    double height = 0;
    for (const auto& c : camera_centres) height += floor.height(c);
    floor.camera_height = height / static_cast<double>(camera_centres.size());
    if (floor.camera_height >= search.min_camera_height) candidates.push_back(floor);
  }
  if (candidates.empty()) return std::nullopt;
  std::size_t largest = 0;
  for (const auto& c : candidates) largest = std::max(largest, c.support);
  std::optional<FloorPlane> lowest;
  for (const auto& c : candidates) {
    if (5 * c.support < largest) continue;
    if (!lowest || c.camera_height > lowest->camera_height) lowest = c;
  }
  return lowest;
}

}  // namespace amos::dense
