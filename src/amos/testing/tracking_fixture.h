#pragma once
// For tests only (library amos_testing): what a tracking or mapping test needs around a synthetic sequence.
//   FrameBuilder           turns a SyntheticView into the map::Frame that tracking takes, as SlamSystem::track does
//                          (ORB extraction, map::buildFrameFeatures with the depth and an optional dynamic mask).
//   RecordingKeyFrameSink  a tracking::KeyFrameSink that records every keyframe handed over (and forwards it to a
//                          real sink, e.g. a mapping::LocalMapper, when given one).
#include <cstddef>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <vector>

#include "amos/feature/orb_extractor.h"
#include "amos/map/frame.h"
#include "amos/map/sensor.h"
#include "amos/testing/synthetic_scene.h"
#include "amos/tracking/keyframe_sink.h"

namespace amos::testing {

class FrameBuilder {
 public:
  explicit FrameBuilder(const core::CameraIntrinsics& intrinsics, const feature::OrbOptions& orb = {},
                        const map::SensorOptions& sensor = {});

  // The next frame (ids 0, 1, 2, ... in call order) from the view's grey image and depth.
  map::Frame build(const SyntheticView& view, double timestamp, const cv::Mat& dynamic_mask = cv::Mat());

  const std::shared_ptr<const map::Sensor>& sensor() const { return sensor_; }

 private:
  feature::OrbExtractor extractor_;
  std::shared_ptr<const map::Sensor> sensor_;
  map::FrameId next_id_ = 0;
};

class RecordingKeyFrameSink final : public tracking::KeyFrameSink {
 public:
  struct Record {
    map::KeyFramePtr kf;
    std::vector<map::MapPointPtr> new_points;
  };

  // next: where the keyframes go on to (not owned; null = nowhere, and the sink is always idle).
  explicit RecordingKeyFrameSink(tracking::KeyFrameSink* next = nullptr) : next_(next) {}

  void insertKeyFrame(const map::KeyFramePtr& kf, std::vector<map::MapPointPtr> new_points) override {
    {
      std::lock_guard lock(mutex_);
      records_.push_back({kf, new_points});
    }
    if (next_) next_->insertKeyFrame(kf, std::move(new_points));
  }
  bool isIdle() const override { return next_ ? next_->isIdle() : true; }
  std::size_t queuedKeyFrames() const override { return next_ ? next_->queuedKeyFrames() : 0; }
  void interruptBundleAdjustment() override {
    {
      std::lock_guard lock(mutex_);
      ++interrupts_;
    }
    if (next_) next_->interruptBundleAdjustment();
  }

  std::vector<Record> records() const {
    std::lock_guard lock(mutex_);
    return records_;
  }
  std::size_t count() const {
    std::lock_guard lock(mutex_);
    return records_.size();
  }
  int interrupts() const {
    std::lock_guard lock(mutex_);
    return interrupts_;
  }

 private:
  tracking::KeyFrameSink* next_;
  mutable std::mutex mutex_;
  std::vector<Record> records_;
  int interrupts_ = 0;
};

}  // namespace amos::testing
