// Local mapping with known answers: on a synthetic sequence the tracker hands its keyframes through a recording
// sink to the mapper, whose map points must lie on the true surfaces and whose keyframe poses must stay at (or
// come back to) the true ones. And the mapping thread's failure contract: an exception while a keyframe is
// processed (here thrown by the after-keyframe hook, where loop closing runs) stops the mapping and reaches the
// tracking thread, never logged and forgotten.
#include "amos/mapping/local_mapper.h"
#include "amos/mapping/local_bundle_adjustment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <set>
#include <shared_mutex>
#include <stdexcept>
#include <string>

#include "amos/core/error.h"
#include "amos/testing/pose_matchers.h"
#include "amos/testing/synthetic_scene.h"
#include "amos/testing/test_camera.h"
#include "amos/testing/tracking_fixture.h"
#include "amos/tracking/tracker.h"

namespace amos::mapping {
namespace {

// A keyframe without keypoints: the mapper's bookkeeping runs on it and finds nothing to do.
map::KeyFramePtr emptyKeyFrame(map::Map& map, map::FrameId id) {
  static const auto sensor =
      std::make_shared<map::Sensor>(testing::testIntrinsics(), map::SensorOptions{}, feature::OrbOptions{});
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

// --- Known answers on a synthetic sequence ---

using amos::testing::PoseNear;
constexpr double kDeg = M_PI / 180;

// Passes keyframes on to the mapper; the one with id `perturb_id` first gets its pose moved by `perturbation`
// (left-multiplied), as if tracking had placed it there.
class PerturbingSink final : public tracking::KeyFrameSink {
 public:
  PerturbingSink(tracking::KeyFrameSink& next, map::Map& map, map::KeyFrameId perturb_id, core::SE3 perturbation)
      : next_(next), map_(map), perturb_id_(perturb_id), perturbation_(perturbation) {}
  void insertKeyFrame(const map::KeyFramePtr& kf, std::vector<map::MapPointPtr> new_points) override {
    if (kf->id() == perturb_id_) {
      std::unique_lock lock(map_.mutex());
      kf->setPose(perturbation_ * kf->T_cw());
    }
    next_.insertKeyFrame(kf, std::move(new_points));
  }
  bool isIdle() const override { return next_.isIdle(); }
  std::size_t queuedKeyFrames() const override { return next_.queuedKeyFrames(); }
  void interruptBundleAdjustment() override { next_.interruptBundleAdjustment(); }

 private:
  tracking::KeyFrameSink& next_;
  map::Map& map_;
  map::KeyFrameId perturb_id_;
  core::SE3 perturbation_;
};

struct MappedSequence {
  std::shared_ptr<map::Map> map;
  std::vector<testing::RecordingKeyFrameSink::Record> keyframes;  // as tracking handed them over
  LocalMappingStats stats;
};

// Tracks `seq` frame by frame (frame id = index) with the mapper in lock-step behind `wrap(mapper)`.
MappedSequence mapSequence(const testing::SyntheticSequence& seq, const LocalMappingOptions& options,
                           const std::function<std::unique_ptr<tracking::KeyFrameSink>(
                               tracking::KeyFrameSink&, map::Map&)>& wrap = {}) {
  MappedSequence out;
  out.map = std::make_shared<map::Map>();
  LocalMapper mapper(options, out.map, /*lock_step=*/true);
  std::unique_ptr<tracking::KeyFrameSink> wrapper = wrap ? wrap(mapper, *out.map) : nullptr;
  testing::RecordingKeyFrameSink sink(wrapper ? wrapper.get() : &mapper);
  tracking::Tracker tracker(tracking::TrackerOptions{}, out.map, &sink);
  testing::FrameBuilder builder(testing::testIntrinsics());
  for (int i = 0; i < seq.size(); ++i) {
    const tracking::TrackResult r = tracker.track(builder.build(seq.view(i), seq.timestamp(i)));
    EXPECT_EQ(r.state, tracking::TrackingState::kOk) << "frame " << i;
  }
  mapper.stop();
  out.keyframes = sink.records();
  out.stats = mapper.stats();
  return out;
}

std::shared_ptr<const testing::SyntheticScene> room() {
  static const auto scene =
      std::make_shared<const testing::SyntheticScene>(testing::texturedRoom(testing::testIntrinsics()));
  return scene;
}

// A slide to the right with a pan to the left, 2 cm and 0.8 deg per frame: a new keyframe every few frames.
const testing::SyntheticSequence& slide() {
  static const testing::SyntheticSequence seq = [] {
    core::Vector6d xi;
    xi << 0.02, 0.002, 0.005, 0.001, -0.8 * kDeg, 0.001;
    return testing::SyntheticSequence(room(), testing::constantVelocityPath(24, xi));
  }();
  return seq;
}

// How far the good map points are from the true surfaces, relative to the depth resolution of RGB-D tracking's
// virtual stereo pair: a point at depth z seen with one pixel of disparity error moves by z^2 / bf (bf = 40 px m),
// so distances are given in units of z^2 / 40 ("pixels of disparity"). Points from depth and points triangulated
// by the mapper are kept apart.
struct PointErrors {
  std::vector<double> depth_mm, depth_px, triangulated_px;  // sorted
  double quantile(const std::vector<double>& v, double q) const {
    return v.empty() ? -1.0 : v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
  }
};

PointErrors pointErrors(const MappedSequence& m) {
  std::set<map::MapPointId> from_depth;
  for (const auto& record : m.keyframes)
    for (const auto& p : record.new_points) from_depth.insert(p->id());
  PointErrors e;
  std::shared_lock lock(m.map->mutex());
  for (const map::MapPointPtr& p : m.map->mapPoints()) {
    if (p->isBad()) continue;
    const double d = room()->distanceToStaticSurface(p->position());
    const double z = p->position().z();  // depth in the first keyframe (the paths here stay near it)
    const double px = d / (z * z / 40.0);
    if (from_depth.count(p->id())) {
      e.depth_mm.push_back(d * 1000);
      e.depth_px.push_back(px);
    } else {
      e.triangulated_px.push_back(px);
    }
  }
  for (auto* v : {&e.depth_mm, &e.depth_px, &e.triangulated_px}) std::sort(v->begin(), v->end());
  return e;
}

// Without bundle adjustment the points are where tracking and triangulation put them: the ones from (exact)
// depth on the surfaces up to the keyframe poses' sub-millimetre errors, the triangulated ones within a fraction of
// a pixel of disparity.
TEST(LocalMapper, NewMapPointsLieOnTheTrueSurfaces) {
  LocalMappingOptions options;
  options.local_ba = false;
  const MappedSequence m = mapSequence(slide(), options);
  ASSERT_GE(m.keyframes.size(), 3u);
  EXPECT_EQ(m.stats.keyframes_processed, static_cast<int>(m.keyframes.size()));
  EXPECT_EQ(m.stats.ba_runs, 0);
  const PointErrors e = pointErrors(m);
  ASSERT_GT(e.depth_mm.size(), 500u);
  ASSERT_GT(e.triangulated_px.size(), 50u);
  EXPECT_LT(e.quantile(e.depth_mm, 0.5), 1.0);
  EXPECT_LT(e.quantile(e.depth_mm, 0.99), 5.0);
  EXPECT_LT(e.quantile(e.triangulated_px, 0.5), 0.25);
  EXPECT_LT(e.quantile(e.triangulated_px, 0.9), 0.75);
}

// With local bundle adjustment the keyframes stay at their true poses and the points near the surfaces: BA fits
// the keypoints' detection noise, which moves far points along their rays by up to about a pixel of disparity.
TEST(LocalMapper, BundleAdjustmentKeepsKeyFramesAtTheTruePoses) {
  const MappedSequence m = mapSequence(slide(), LocalMappingOptions{});
  ASSERT_GE(m.keyframes.size(), 3u);
  EXPECT_GT(m.stats.ba_runs, 0);
  EXPECT_GT(m.stats.points_triangulated, 50);
  const PointErrors e = pointErrors(m);
  EXPECT_LT(e.quantile(e.depth_px, 0.5), 0.25);
  EXPECT_LT(e.quantile(e.depth_px, 0.9), 0.75);
  EXPECT_LT(e.quantile(e.triangulated_px, 0.5), 0.25);
  EXPECT_LT(e.quantile(e.triangulated_px, 0.9), 0.75);
  std::shared_lock lock(m.map->mutex());
  int good_keyframes = 0;
  for (const map::KeyFramePtr& kf : m.map->keyFrames()) {
    if (kf->isBad()) continue;
    ++good_keyframes;
    EXPECT_THAT(kf->T_cw(), PoseNear(slide().T_cw(static_cast<int>(kf->frameId())), 0.005, 0.2 * kDeg))
        << "keyframe " << kf->id() << " (frame " << kf->frameId() << ")";
  }
  EXPECT_GE(good_keyframes, 3);
}

// The third keyframe arrives 3 cm and 1 deg off its true pose: local bundle adjustment, against the points the
// earlier keyframes fixed, brings it back; without it the error stays.
TEST(LocalMapper, BundleAdjustmentBringsAMisplacedKeyFrameBack) {
  core::Vector6d xi;
  xi << 0.02, -0.015, 0.01, 0.01, -0.01, 0.01;
  const core::SE3 perturbation = core::expSE3(xi);
  const map::KeyFrameId misplaced = 2;
  auto perturbing = [&](tracking::KeyFrameSink& next, map::Map& map) -> std::unique_ptr<tracking::KeyFrameSink> {
    return std::make_unique<PerturbingSink>(next, map, misplaced, perturbation);
  };
  auto poseOf = [](const MappedSequence& m) {
    std::shared_lock lock(m.map->mutex());
    const map::KeyFramePtr kf = m.map->keyFrame(misplaced);
    EXPECT_TRUE(kf && !kf->isBad());
    return std::make_pair(kf->T_cw(), static_cast<int>(kf->frameId()));
  };
  LocalMappingOptions options;
  options.cull_keyframes = false;  // keep the misplaced keyframe to look at
  const auto [adjusted, frame] = poseOf(mapSequence(slide(), options, perturbing));
  EXPECT_THAT(adjusted, PoseNear(slide().T_cw(frame), 0.005, 0.2 * kDeg));

  options.local_ba = false;
  const auto [kept, same_frame] = poseOf(mapSequence(slide(), options, perturbing));
  ASSERT_EQ(frame, same_frame);
  EXPECT_THAT(kept, ::testing::Not(PoseNear(slide().T_cw(frame), 0.02, 0.5 * kDeg)));
}

// Global bundle adjustment (run after a loop closure): every keyframe but the first moved off its pose after
// mapping, as a pose graph leaves them; the adjustment of the whole map brings each back against the points, and
// the first keyframe, the gauge, does not move.
TEST(GlobalBundleAdjustment, BringsEveryKeyFrameBackAndKeepsTheFirst) {
  LocalMappingOptions options;
  options.local_ba = false;
  options.cull_keyframes = false;
  const MappedSequence m = mapSequence(slide(), options);
  std::vector<map::KeyFramePtr> kfs;
  core::SE3 first_before;
  {
    std::unique_lock lock(m.map->mutex());
    kfs = m.map->keyFrames();
    ASSERT_GE(kfs.size(), 4u);
    first_before = kfs.front()->T_cw();
    for (std::size_t k = 1; k < kfs.size(); ++k) {
      core::Vector6d xi;
      const double s = k % 2 ? 1.0 : -1.0;
      xi << 0.01 * s, 0.005, -0.008 * s, 0.004, -0.006 * s, 0.003;  // ~1.4 cm and ~0.5 deg
      kfs[k]->setPose(core::expSE3(xi) * kfs[k]->T_cw());
      EXPECT_THAT(kfs[k]->T_cw(), ::testing::Not(PoseNear(slide().T_cw(static_cast<int>(kfs[k]->frameId())),
                                                            0.01, 0.3 * kDeg)));
    }
  }
  const BaStats stats = runGlobalBundleAdjustment(*m.map, BundleAdjustmentOptions{}, nullptr);
  EXPECT_EQ(stats.adjusted_keyframes, static_cast<int>(kfs.size()));
  EXPECT_EQ(stats.fixed_keyframes, 0);
  std::shared_lock lock(m.map->mutex());
  EXPECT_THAT(kfs.front()->T_cw(), PoseNear(first_before, 1e-12, 1e-12));
  for (const map::KeyFramePtr& kf : kfs) {
    EXPECT_THAT(kf->T_cw(), PoseNear(slide().T_cw(static_cast<int>(kf->frameId())), 0.005, 0.2 * kDeg))
        << "keyframe " << kf->id();
  }
}

}  // namespace
}  // namespace amos::mapping
