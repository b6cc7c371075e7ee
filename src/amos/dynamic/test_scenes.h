#pragma once
// Cameras and frames the dynamic module's tests build their scenes on (header-only, included by *_test.cc only).
#include "amos/core/camera.h"

namespace amos::dynamic {

// TUM fr3's colour camera without distortion, 640 x 480.
inline core::PinholeCamera testCamera() {
  core::CameraIntrinsics intr;
  intr.fx = 535.4, intr.fy = 539.2, intr.cx = 320.1, intr.cy = 247.6;
  return core::PinholeCamera(intr);
}

}  // namespace amos::dynamic
