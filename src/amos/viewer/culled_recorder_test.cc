#include "amos/viewer/culled_recorder.h"

#include <gtest/gtest.h>

#include <mutex>
#include <shared_mutex>

namespace amos::viewer {
namespace {

// Points removed from the map while the recorder looks: those that meet the dynamic culling rule are kept, the
// others (culled for another reason) are not.
TEST(CulledPointRecorder, KeepsThePointsRemovedAsDynamic) {
  auto m = std::make_shared<map::Map>();
  {
    std::unique_lock lock(m->mutex());
    for (int i = 0; i < 4; ++i)
      m->addMapPoint(std::make_shared<map::MapPoint>(m->newMapPointId(), Eigen::Vector3d(i, 2, 3), 0, 0));
    m->mapPoint(1)->increaseDynamicHits(4);
    m->mapPoint(1)->increaseMaskedViews(6);
  }
  CulledPointRecorder recorder(std::chrono::milliseconds(1));
  recorder.start(m);
  {
    std::unique_lock lock(m->mutex());
    m->setMapPointBad(m->mapPoint(1));
    m->setMapPointBad(m->mapPoint(2));
  }
  const std::vector<PointSample> culled = recorder.finish();
  ASSERT_EQ(culled.size(), 1u);
  EXPECT_EQ(culled[0].id, 1u);
  EXPECT_FLOAT_EQ(culled[0].position.x(), 1.0f);
  EXPECT_EQ(m.use_count(), 1);  // released
}

TEST(CulledPointRecorder, WithoutAMapRecordsNothing) {
  CulledPointRecorder recorder;
  recorder.start(nullptr);
  EXPECT_TRUE(recorder.finish().empty());
}

}  // namespace
}  // namespace amos::viewer
