#include "amos/dense/voxel_mean_cloud.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"

namespace amos::dense {
namespace {

TEST(VoxelMeanCloud, KeepsOneMeanPointPerVoxelInTheOrderReached) {
  VoxelMeanCloud cloud(0.1);
  cloud.add({0.01, 0.02, 0.03}, {1, 0, 0});
  cloud.add({0.25, 0.05, 0.05}, {0, 0, 1});  // another voxel
  cloud.add({0.03, 0.04, 0.05}, {0, 1, 0});  // the first voxel again
  cloud.add({-0.01, 0.05, 0.05}, {0, 0, 0});  // x < 0: the voxel below the origin, not the first one
  ASSERT_EQ(cloud.voxels(), 3u);
  const DenseCloud out = cloud.cloud();
  ASSERT_EQ(out.points.size(), 3u);
  EXPECT_TRUE(out.points[0].isApprox(Eigen::Vector3d(0.02, 0.03, 0.04)));
  EXPECT_EQ(out.colours[0], (Rgb{128, 128, 0}));  // the mean of red and green, rounded
  EXPECT_TRUE(out.points[1].isApprox(Eigen::Vector3d(0.25, 0.05, 0.05)));
  EXPECT_EQ(out.colours[1], (Rgb{0, 0, 255}));
  EXPECT_TRUE(out.points[2].isApprox(Eigen::Vector3d(-0.01, 0.05, 0.05)));
}

TEST(VoxelMeanCloud, ANonPositiveVoxelIsAnError) {
  EXPECT_THROW(VoxelMeanCloud(0.0), core::Error);
  EXPECT_THROW(VoxelMeanCloud(-0.02), core::Error);
}

}  // namespace
}  // namespace amos::dense
