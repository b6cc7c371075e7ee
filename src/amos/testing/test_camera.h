#pragma once
// For tests only: the cameras the tests build their scenes on, written once (header-only, no link dependency, so
// that any module's tests can use it). A test that needs "some camera" takes testIntrinsics(); one whose scene is
// written by hand takes smallTestIntrinsics(); one that reads real frames takes the camera those frames were
// recorded with.
#include "amos/core/camera.h"
#include "amos/geometry/pose_optimizer.h"

namespace amos::testing {

// TUM fr3's colour camera without distortion, 640 x 480: configs/tum3.yaml and the camera of the synthetic
// sequences (synth::SensorOptions::tumFr3Intrinsics(); testing_test checks that they agree).
inline core::CameraIntrinsics testIntrinsics() {
  core::CameraIntrinsics k;
  k.fx = 535.4, k.fy = 539.2, k.cx = 320.1, k.cy = 247.6;
  k.width = 640, k.height = 480;
  return k;
}
inline core::PinholeCamera testCamera() { return core::PinholeCamera(testIntrinsics()); }

// The RGB-D virtual stereo projection of testIntrinsics() with the configs' baseline (Camera.bf = 40).
inline geometry::StereoProjection testProjection() {
  const core::CameraIntrinsics k = testIntrinsics();
  return {k.fx, k.fy, k.cx, k.cy, 40.0};
}

// A 120 x 100 camera with f = 100 px and the principal point in the middle: scenes small enough to write by hand.
inline core::CameraIntrinsics smallTestIntrinsics() {
  core::CameraIntrinsics k;
  k.fx = k.fy = 100, k.cx = 60, k.cy = 50, k.width = 120, k.height = 100;
  return k;
}
inline core::PinholeCamera smallTestCamera() { return core::PinholeCamera(smallTestIntrinsics()); }

// Bonn RGB-D Dynamic (ASUS Xtion) with its distortion, from the data set's README (configs/bonn.yaml), for the
// tests that read real Bonn frames.
inline core::CameraIntrinsics bonnIntrinsics() {
  core::CameraIntrinsics k;
  k.fx = 542.822841, k.fy = 542.576870, k.cx = 315.593520, k.cy = 237.756098;
  k.k1 = 0.039903, k.k2 = -0.099343, k.p1 = -0.000730, k.p2 = -0.000144;
  k.width = 640, k.height = 480;
  return k;
}

// TUM fr1 with its distortion (configs/tum1.yaml): a real calibration with strong radial distortion.
inline core::CameraIntrinsics tumFr1Intrinsics() {
  core::CameraIntrinsics k;
  k.fx = 517.306408, k.fy = 516.469215, k.cx = 318.643040, k.cy = 255.313989;
  k.k1 = 0.262383, k.k2 = -0.953104, k.p1 = -0.005358, k.p2 = 0.002628, k.k3 = 1.163314;
  k.width = 640, k.height = 480;
  return k;
}

}  // namespace amos::testing
