#include "amos/testing/tracking_fixture.h"

namespace amos::testing {

FrameBuilder::FrameBuilder(const core::CameraIntrinsics& intrinsics, const feature::OrbOptions& orb,
                           const map::SensorOptions& sensor)
    : extractor_(orb), sensor_(std::make_shared<map::Sensor>(intrinsics, sensor, orb)) {}

map::Frame FrameBuilder::build(const SyntheticView& view, double timestamp, const cv::Mat& dynamic_mask) {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  extractor_.extract(view.gray, keypoints, descriptors);
  auto features = map::buildFrameFeatures(*sensor_, keypoints, descriptors, view.depth, dynamic_mask);
  map::Frame frame =
      map::makeFrame(next_id_++, timestamp, sensor_, std::move(features), map::makeThumbnail(view.gray), dynamic_mask);
  if (!dynamic_mask.empty()) frame.depth_image = view.depth;
  return frame;
}

}  // namespace amos::testing
