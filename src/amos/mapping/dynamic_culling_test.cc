#include "amos/mapping/dynamic_culling.h"

#include <gtest/gtest.h>

#include "amos/core/error.h"
#include "amos/testing/test_camera.h"

namespace amos::mapping {
namespace {

std::shared_ptr<const map::Sensor> sensor() {
  return std::make_shared<map::Sensor>(testing::testIntrinsics(), map::SensorOptions{}, feature::OrbOptions{});
}

TEST(DynamicCulling, CullsPointsSeenOnMoversOftenEnough) {
  map::Map m;
  auto f = std::make_shared<map::FrameFeatures>();
  f->descriptors = cv::Mat::zeros(4, 32, CV_8U);
  for (int i = 0; i < 4; ++i) {
    f->keys.emplace_back(cv::Point2f(100.0f + 50 * i, 100.0f), 7.0f, 0.0f, 0.0f, 0);
    f->depth.push_back(2.0f);
    f->u_right.push_back(f->keys.back().pt.x - 10.0f);
  }
  f->grid = feature::KeypointGrid(cv::Rect2d(0, 0, 640, 480), f->keys);
  const map::Frame frame = map::makeFrame(0, 0.0, sensor(), f, cv::Mat(), cv::Mat());
  auto kf = std::make_shared<map::KeyFrame>(m.newKeyFrameId(), frame);
  m.addKeyFrame(kf);
  std::vector<map::MapPointPtr> p;
  for (int i = 0; i < 4; ++i) p.push_back(m.createMapPoint(Eigen::Vector3d(i, 0, 2), kf, i, 0));
  // p0: 5 dynamic of 6 masked views -> culled. p1: 2 of 2 (too few hits). p2: 3 of 10 (mostly static).
  // p3: never in a mask.
  p[0]->increaseDynamicHits(5);
  p[0]->increaseMaskedViews(6);
  p[1]->increaseDynamicHits(2);
  p[1]->increaseMaskedViews(2);
  p[2]->increaseDynamicHits(3);
  p[2]->increaseMaskedViews(10);
  EXPECT_EQ(cullDynamicPoints(m, DynamicCullingOptions{}), 1);
  EXPECT_TRUE(p[0]->isBad());
  EXPECT_FALSE(p[1]->isBad());
  EXPECT_FALSE(p[2]->isBad());
  EXPECT_FALSE(p[3]->isBad());
  EXPECT_EQ(kf->mapPoint(0), nullptr);
  EXPECT_EQ(m.numMapPoints(), 3u);
}

TEST(DynamicCulling, InvalidOptionsAreRejected) {
  DynamicCullingOptions o;
  o.min_ratio = 0;
  EXPECT_THROW(o.check(), core::Error);
}

}  // namespace
}  // namespace amos::mapping
