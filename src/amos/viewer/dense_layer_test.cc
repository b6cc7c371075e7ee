#include "amos/viewer/dense_layer.h"

#include <gtest/gtest.h>

#include <cstring>

#include "amos/core/error.h"
#include "amos/viewer/test_run_folder.h"

namespace amos::viewer {
namespace {

template <typename T>
T at(const std::string& bytes, std::size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

TEST(DenseLayer, EncodesCountsPositionsIndicesThenColours) {
  const ColouredGeometry g = test::floorAndWall(-1, 1, 0, 2, 0.5f);
  const std::string bytes = encodeDenseLayer(g);
  ASSERT_EQ(bytes.size(), 8u + 8 * 12 + 4 * 12 + 8 * 3);
  EXPECT_EQ(at<std::uint32_t>(bytes, 0), 8u);
  EXPECT_EQ(at<std::uint32_t>(bytes, 4), 4u);
  EXPECT_EQ(at<float>(bytes, 8 + 4 * 3), g.xyz[3]);  // vertex 1's x
  EXPECT_EQ(at<std::uint32_t>(bytes, 8 + 96 + 4 * 5), g.triangles[5]);
  EXPECT_EQ(static_cast<std::uint8_t>(bytes[8 + 96 + 48 + 12]), g.rgb[12]);
}

TEST(DenseLayer, InconsistentSizesAreAnError) {
  ColouredGeometry g;
  g.xyz = {1, 2, 3};
  g.rgb = {1, 2};
  EXPECT_THROW(encodeDenseLayer(g), core::Error);
}

TEST(DenseLayer, ThinningKeepsAtMostTheLimitEvenly) {
  const ColouredGeometry cloud = test::gridCloud(0, 1, 0, 1, 0, 1000, 9, 8, 7);
  const ColouredGeometry thin = thinPoints(cloud, 300);
  EXPECT_LE(thin.vertexCount(), 300u);
  EXPECT_GE(thin.vertexCount(), 250u);
  EXPECT_EQ(thin.rgb.size(), thin.xyz.size());
  EXPECT_EQ(thin.xyz[3], cloud.xyz[3 * 4]);  // every 4th point: the second kept is point 4
  EXPECT_EQ(thinPoints(cloud, 5000).vertexCount(), 1000u);
}

}  // namespace
}  // namespace amos::viewer
