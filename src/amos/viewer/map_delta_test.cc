#include "amos/viewer/map_delta.h"

#include <gtest/gtest.h>

#include <memory>
#include <mutex>

namespace amos::viewer {
namespace {

PointSample point(std::uint64_t id, float x, int hits = 0, int masked_views = 0) {
  return {id, Eigen::Vector3f(x, 0, 1), hits, masked_views};
}

TEST(MapDelta, SendsNewMovedAndRemovedPointsOnly) {
  MapSnapshot before, after;
  before.points = {point(1, 0), point(2, 1), point(3, 2), point(5, 4, 3, 5)};
  // 1 unchanged, 2 moved by 0.5 mm (jitter: not sent), 3 moved by 5 cm, 4 new, 5 removed (seen in dynamic masks).
  after.points = {point(1, 0), point(2, 1.0005f), point(3, 2.05f), point(4, 3)};
  const MapDelta d = diffMaps(before, after);
  ASSERT_EQ(d.points.size(), 2u);
  EXPECT_EQ(d.points[0].id, 3u);
  EXPECT_FLOAT_EQ(d.points[0].position.x(), 2.05f);
  EXPECT_EQ(d.points[1].id, 4u);
  EXPECT_EQ(d.removed, std::vector<std::uint64_t>{5});
  ASSERT_EQ(d.culled.size(), 1u);
  EXPECT_EQ(d.culled[0].id, 5u);
  EXPECT_TRUE(diffMaps(after, after).empty());
}

TEST(MapDelta, RemovedPointCountsAsCulledOnlyUnderTheCullingRule) {
  MapSnapshot before, after;
  // Too few hits; enough hits but in under half of its masked views; both met.
  before.points = {point(7, 0, 2, 2), point(8, 0, 3, 7), point(9, 0, 3, 6)};
  const MapDelta d = diffMaps(before, after);
  EXPECT_EQ(d.removed.size(), 3u);
  ASSERT_EQ(d.culled.size(), 1u);
  EXPECT_EQ(d.culled[0].id, 9u);
}

TEST(MapDelta, KeyFramesThatTurnedOrMovedAreSentAgain) {
  MapSnapshot before, after;
  KeyFrameSample a{1, Eigen::Vector3f::Zero(), Eigen::Quaternionf::Identity()};
  KeyFrameSample b{2, Eigen::Vector3f(1, 0, 0), Eigen::Quaternionf::Identity()};
  before.keyframes = {a, b};
  KeyFrameSample turned = a;
  turned.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(0.1f, Eigen::Vector3f::UnitY()));
  after.keyframes = {turned};
  const MapDelta d = diffMaps(before, after);
  ASSERT_EQ(d.keyframes.size(), 1u);
  EXPECT_EQ(d.keyframes[0].id, 1u);
  EXPECT_EQ(d.removed_keyframes, std::vector<std::uint64_t>{2});
}

TEST(MapDelta, SnapshotCopiesTheGoodPointsOfTheMap) {
  map::Map m;
  {
    std::unique_lock lock(m.mutex());
    for (int i = 0; i < 3; ++i)
      m.addMapPoint(std::make_shared<map::MapPoint>(m.newMapPointId(), Eigen::Vector3d(i, 2, 3), 0, 0));
    m.mapPoint(1)->increaseDynamicHits(4);
    m.mapPoint(1)->increaseMaskedViews(6);
  }
  const MapSnapshot s = takeMapSnapshot(m);
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.points[2].id, 2u);
  EXPECT_FLOAT_EQ(s.points[2].position.x(), 2.0f);
  EXPECT_EQ(s.points[1].dynamic_hits, 4);
  EXPECT_EQ(s.points[1].masked_views, 6);
  EXPECT_TRUE(s.keyframes.empty());
}

}  // namespace
}  // namespace amos::viewer
