// The mapping thread's failure contract: an exception while a keyframe is processed (here thrown by the
// after-keyframe hook, where loop closing runs) stops the mapping and reaches the tracking thread, never logged
// and forgotten.
#include "amos/mapping/local_mapper.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>

#include "amos/core/error.h"

namespace amos::mapping {
namespace {

// A keyframe without keypoints: the mapper's bookkeeping runs on it and finds nothing to do.
map::KeyFramePtr emptyKeyFrame(map::Map& map, map::FrameId id) {
  core::CameraIntrinsics c;
  c.fx = c.fy = 500;
  c.cx = 320;
  c.cy = 240;
  static const auto sensor = std::make_shared<map::Sensor>(c, map::SensorOptions{}, feature::OrbOptions{});
  auto features = std::make_shared<map::FrameFeatures>();
  features->descriptors = cv::Mat(0, 32, CV_8U);
  features->grid = feature::KeypointGrid(cv::Rect2d(0, 0, 640, 480), features->keys);
  map::Frame frame = map::makeFrame(id, static_cast<double>(id), sensor, features,
                                    map::makeThumbnail(cv::Mat(480, 640, CV_8U, cv::Scalar(0))), cv::Mat());
  frame.setPose(core::SE3::Identity());
  auto kf = std::make_shared<map::KeyFrame>(map.newKeyFrameId(), frame);
  map.addKeyFrame(kf);
  return kf;
}

// Throws on the keyframe with id `bad`.
KeyFrameHook failingOn(map::KeyFrameId bad) {
  return [bad](const map::KeyFramePtr& kf) {
    if (kf->id() == bad) throw std::runtime_error("pose graph diverged");
  };
}

std::string messageOf(const LocalMapper& mapper) {
  try {
    mapper.rethrowIfFailed();
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

// Lock-step (deterministic): the keyframe whose processing failed reports it from its own insertKeyFrame().
TEST(LocalMapperFailure, LockStepReportsTheFailureFromTheKeyFramesInsert) {
  auto map = std::make_shared<map::Map>();
  LocalMapper mapper(LocalMappingOptions{}, map, /*lock_step=*/true, nullptr, failingOn(1));
  EXPECT_FALSE(mapper.failure());
  mapper.insertKeyFrame(emptyKeyFrame(*map, 0), {});
  EXPECT_THROW(mapper.insertKeyFrame(emptyKeyFrame(*map, 1), {}), core::Error);
  ASSERT_TRUE(mapper.failure());
  const std::string message = messageOf(mapper);
  EXPECT_NE(message.find("local mapping failed on keyframe 1: pose graph diverged"), std::string::npos) << message;
  // Mapping has stopped: a later keyframe is refused with the same failure, and stop() returns.
  EXPECT_THROW(mapper.insertKeyFrame(emptyKeyFrame(*map, 2), {}), core::Error);
  mapper.stop();
  EXPECT_EQ(mapper.stats().keyframes_processed, 1);
}

// Threaded: the failure is handed over under the mutex; the next insert or rethrowIfFailed() gets it, queued
// keyframes are dropped, and nothing waits forever.
TEST(LocalMapperFailure, ThreadedFailureReachesTheNextInsert) {
  auto map = std::make_shared<map::Map>();
  LocalMapper mapper(LocalMappingOptions{}, map, /*lock_step=*/false, nullptr, failingOn(0));
  mapper.insertKeyFrame(emptyKeyFrame(*map, 0), {});
  mapper.waitUntilIdle();
  ASSERT_TRUE(mapper.failure());
  EXPECT_THROW(mapper.rethrowIfFailed(), core::Error);
  EXPECT_THROW(mapper.insertKeyFrame(emptyKeyFrame(*map, 1), {}), core::Error);
  EXPECT_TRUE(mapper.isIdle());
  mapper.stop();
  EXPECT_EQ(mapper.stats().keyframes_processed, 0);
}

TEST(LocalMapperFailure, NoFailureNoError) {
  auto map = std::make_shared<map::Map>();
  std::atomic<int> seen{0};
  LocalMapper mapper(LocalMappingOptions{}, map, /*lock_step=*/false, nullptr,
                     [&seen](const map::KeyFramePtr&) { ++seen; });
  for (map::FrameId id = 0; id < 3; ++id) mapper.insertKeyFrame(emptyKeyFrame(*map, id), {});
  mapper.stop();
  EXPECT_EQ(seen.load(), 3);
  EXPECT_FALSE(mapper.failure());
  EXPECT_NO_THROW(mapper.rethrowIfFailed());
}

}  // namespace
}  // namespace amos::mapping
