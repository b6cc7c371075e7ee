#pragma once
// For tests that drive system::SlamSystem directly, without the pipeline (header-only: the tests that use it link
// the system module anyway). The core extracts nothing itself (stage A of the pipeline does, frame_scheduler.h), so
// a test hands it the features as stage A would: the frame's grey image and its ORB features.
#include <opencv2/core.hpp>

#include <utility>

#include "amos/feature/orb_extractor.h"
#include "amos/io/rgbd_frame.h"
#include "amos/system/frame_scheduler.h"
#include "amos/system/slam_system.h"

namespace amos::testing {

// The frame with its ORB features (extracted by `orb`, which must have the SLAM system's ORB options) and an
// optional dynamic mask, ready for SlamSystem::track.
inline system::TrackInput trackInput(const feature::OrbExtractor& orb, const io::RgbdFrame& frame,
                                     cv::Mat dynamic_mask = cv::Mat()) {
  system::TrackInput input;
  input.timestamp = frame.timestamp;
  input.depth = frame.depth;
  input.features.gray = system::toGray(frame);
  orb.extract(input.features.gray, input.features.keypoints, input.features.descriptors);
  input.dynamic_mask = std::move(dynamic_mask);
  return input;
}

}  // namespace amos::testing
