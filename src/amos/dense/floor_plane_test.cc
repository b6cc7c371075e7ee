#include "amos/dense/floor_plane.h"

#include <gtest/gtest.h>

namespace amos::dense {
namespace {

// A 6 x 6 m floor at z = 0, a 2 x 1 m table top at z = 0.75 and a wall at x = 3.
std::vector<Eigen::Vector3d> roomPoints() {
  std::vector<Eigen::Vector3d> p;
  for (double x = -3; x <= 3; x += 0.04)
    for (double y = -3; y <= 3; y += 0.04) p.emplace_back(x, y, 0.0);
  for (double x = 0; x <= 2; x += 0.04)
    for (double y = 0; y <= 1; y += 0.04) p.emplace_back(x, y, 0.75);
  for (double y = -3; y <= 3; y += 0.04)
    for (double z = 0; z <= 2.5; z += 0.04) p.emplace_back(3.0, y, z);
  return p;
}

TEST(FloorPlane, FindsTheLowestLevelPlaneBelowTheCameras) {
  const std::vector<Eigen::Vector3d> centres = {{0, 0, 1.4}, {1, 0.5, 1.5}};
  // Cameras tilted down and sideways a little: their image-down axes still point roughly down.
  const std::vector<Eigen::Vector3d> down = {Eigen::Vector3d(0.3, 0, -1).normalized(), Eigen::Vector3d(0, 0.2, -1).normalized()};
  const auto floor = findFloor(roomPoints(), centres, down);
  ASSERT_TRUE(floor.has_value());
  EXPECT_GT(floor->normal.z(), 0.999);
  EXPECT_NEAR(floor->offset, 0.0, 0.01);
  EXPECT_NEAR(floor->camera_height, 1.45, 0.01);
}

TEST(FloorPlane, TheTableIsNoFloorEvenWhenLarger) {
  std::vector<Eigen::Vector3d> points;
  for (double x = -2; x <= 2; x += 0.04)
    for (double y = -1; y <= 3; y += 0.04) points.emplace_back(x, y, 0.75);  // a big table
  for (double x = -1; x <= 1; x += 0.04)
    for (double y = -3; y <= -1; y += 0.04) points.emplace_back(x, y, 0.0);  // floor seen beside it
  const auto floor = findFloor(points, {{0, 0, 1.6}}, {{0, 0, -1}});
  ASSERT_TRUE(floor.has_value());
  EXPECT_NEAR(floor->offset, 0.0, 0.01);
}

TEST(FloorPlane, NoFloorWhenNoPlaneLiesBelowTheCameras) {
  std::vector<Eigen::Vector3d> wall;
  for (double y = -3; y <= 3; y += 0.04)
    for (double z = 0; z <= 2.5; z += 0.04) wall.emplace_back(3.0, y, z);
  EXPECT_FALSE(findFloor(wall, {{0, 0, 1.4}}, {{0, 0, -1}}).has_value());
  EXPECT_FALSE(findFloor({}, {{0, 0, 1.4}}, {{0, 0, -1}}).has_value());
}

}  // namespace
}  // namespace amos::dense
