#pragma once
// For tests that drive system::SlamSystem directly, without the pipeline (header-only: the tests that use it link
// the system module anyway). The core extracts nothing itself (stage A of the pipeline does, frame_scheduler.h), so
// a test hands it the features as stage A would: the frame's grey image and its ORB features.
#include <opencv2/core.hpp>

#include "amos/feature/orb_extractor.h"
#include "amos/io/rgbd_frame.h"
#include "amos/system/frame_scheduler.h"
#include "amos/system/slam_system.h"

namespace amos::testing {

// The frame's ORB features, extracted by `orb` (which must have the SLAM system's ORB options).
inline system::ExtractedFeatures extractFeatures(const feature::OrbExtractor& orb, const io::RgbdFrame& frame) {
  system::ExtractedFeatures features;
  features.gray = system::toGray(frame);
  orb.extract(features.gray, features.keypoints, features.descriptors);
  return features;
}

}  // namespace amos::testing
