#pragma once
// The floor, found in the dense map without an IMU. Gravity is unknown, but a hand-held or robot-borne RGB-D camera
// is held roughly upright: the mean of the cameras' image-down axes (+y of the camera, in the world) points
// roughly down. The floor is then the lowest large plane below the cameras whose normal agrees with that axis:
//   1. the surface points are thinned to one per 5 cm cell;
//   2. planes are taken out one after another by RANSAC (largest first) until the rest is small;
//   3. a plane is a floor candidate when its normal is within 30 degrees of the mean up axis (-down) and the
//      cameras are on its upper side, at least 0.3 m above it (a table under a camera held over it still counts:
//      that is why the lowest plane wins);
//   4. of the candidates with at least a fifth of the largest candidate's points, the lowest (the farthest below
//      the cameras) is the floor.
// RANSAC here is a small seeded loop rather than Open3D's SegmentPlane, whose OpenMP threads draw from one global
// generator: its planes change from run to run.
#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace amos::dense {

struct FloorPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, pointing up (towards the cameras)
  double offset = 0;                                  // normal . p + offset = height of p above the floor
  std::size_t support = 0;                            // surface points on it (after thinning)
  double camera_height = 0;                           // mean height of the cameras above it (m)
  double height(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
};

struct FloorSearch {
  double thinning_cell = 0.05;    // m
  double inlier_distance = 0.03;  // m, a point this near a plane lies on it
  double max_tilt_deg = 30;       // normal against the cameras' mean up axis
  double min_camera_height = 0.3; // m
  int max_planes = 8;
  int iterations = 300;           // RANSAC draws per plane
  unsigned seed = 1;
};

// `points`: the dense map's surface; `camera_centres` and `camera_down_axes`: the cameras' positions and image-down
// axes (T_wc's translation and second rotation column), in the same world frame. std::nullopt when no plane fits.
std::optional<FloorPlane> findFloor(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& camera_centres,
                                    const std::vector<Eigen::Vector3d>& camera_down_axes,
                                    const FloorSearch& search = {});

}  // namespace amos::dense
