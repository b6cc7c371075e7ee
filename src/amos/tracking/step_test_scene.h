#pragma once
// For the tracking steps' tests only (header-only, included by *_test.cc here): frames of the textured synthetic
// room at known poses, and a map made from one of them, so that each step can be checked against the truth.
#include <cmath>
#include <memory>
#include <mutex>

#include "amos/map/frame.h"
#include "amos/map/map.h"
#include "amos/testing/synthetic_scene.h"
#include "amos/testing/test_camera.h"
#include "amos/testing/tracking_fixture.h"
#include "amos/tracking/keyframe_insertion.h"

namespace amos::tracking::step_test {

constexpr double kDeg = M_PI / 180;

inline std::shared_ptr<const testing::SyntheticScene> room() {
  static const auto scene =
      std::make_shared<const testing::SyntheticScene>(testing::texturedRoom(testing::testIntrinsics()));
  return scene;
}

// A camera pose from a twist (translation m, rotation rad; world frame, core::expSE3) applied to the identity.
inline core::SE3 poseAt(double tx, double ty, double tz, double rx, double ry, double rz) {
  core::Vector6d xi;
  xi << tx, ty, tz, rx, ry, rz;
  return testing::constantVelocityPath(2, xi)[1];
}

// The room seen from T_cw as tracking takes it (ORB features, depth; no pose set, no matches).
class RoomFrames {
 public:
  RoomFrames() : builder_(testing::testIntrinsics()) {}
  map::Frame frame(const core::SE3& T_cw, const cv::Mat& dynamic_mask = cv::Mat()) {
    const testing::SyntheticView view = room()->render(T_cw);
    map::Frame frame = builder_.build(view, 1000.0 + 0.033 * next_++, dynamic_mask);
    frame.resetMatches();
    return frame;
  }

 private:
  testing::FrameBuilder builder_;
  int next_ = 0;
};

// A map whose first keyframe is `frame` at pose T_cw, with a point at every keypoint with depth (the frame's
// matches are set to them).
struct MapFromFrame {
  std::shared_ptr<map::Map> map = std::make_shared<map::Map>();
  map::KeyFramePtr kf;
};
inline MapFromFrame mapFrom(map::Frame& frame, const core::SE3& T_cw) {
  MapFromFrame out;
  frame.setPose(T_cw);
  out.kf = insertFirstKeyFrame(*out.map, frame, nullptr).kf;
  return out;
}

}  // namespace amos::tracking::step_test
