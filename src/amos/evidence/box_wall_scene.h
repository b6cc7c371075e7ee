#pragma once
// The scene of the long-baseline tests (header-only, included by *_test.cc only): a textured wall and the textured
// front face of a box moving in front of it, rendered from cameras looking along +z.
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "amos/core/camera.h"
#include "amos/evidence/baseline_tracks.h"
#include "amos/dynamic/corner_tracking.h"
#include "amos/dynamic/dynamic_options.h"
#include "amos/dynamic/test_scenes.h"
#include "amos/testing/test_camera.h"

namespace amos::evidence::box_wall {

using namespace dynamic;  // NOLINT(google-build-using-namespace): the front end's types

// A textured wall 3 m in front of the world origin (plane z = 3) and the textured front face of a box (a square of
// 0.6 m on the plane z = 1.5, centred at x = box_x), its texture moving with it; cameras look along +z without
// rotation, from `centre`. The texture is value noise (random values on a 1 cm grid, bilinear), which has no period
// for LK to slip by.
inline double texture(double x, double y) {
  static const cv::Mat grid = [] {
    cv::Mat g(400, 400, CV_32F);
    cv::RNG rng(7);
    rng.fill(g, cv::RNG::UNIFORM, 40, 215);
    return g;
  }();
  const double gx = (x + 2.0) * 100, gy = (y + 2.0) * 100;  // 1 cm cells over [-2, 2) m
  const int x0 = std::clamp(static_cast<int>(gx), 0, grid.cols - 2), y0 = std::clamp(static_cast<int>(gy), 0, grid.rows - 2);
  const double ax = std::clamp(gx - x0, 0.0, 1.0), ay = std::clamp(gy - y0, 0.0, 1.0);
  const auto at = [&](int r, int c) { return static_cast<double>(grid.at<float>(r, c)); };
  return (1 - ay) * ((1 - ax) * at(y0, x0) + ax * at(y0, x0 + 1)) + ay * ((1 - ax) * at(y0 + 1, x0) + ax * at(y0 + 1, x0 + 1));
}

struct Frame {
  cv::Mat gray, depth;
};

inline Frame render(const core::PinholeCamera& camera, const Eigen::Vector3d& centre, double box_x) {
  Frame f{cv::Mat(camera.height(), camera.width(), CV_8U), cv::Mat(camera.height(), camera.width(), CV_32F)};
  for (int v = 0; v < camera.height(); ++v)
    for (int u = 0; u < camera.width(); ++u) {
      const Eigen::Vector3d ray = camera.backProject(u, v, 1.0);
      const double t_box = 1.5 - centre.z();
      const Eigen::Vector3d hit = centre + t_box * ray;
      const bool on_box = std::abs(hit.x() - box_x) <= 0.3 && std::abs(hit.y()) <= 0.3;
      double value;
      if (on_box) {
        value = texture(hit.x() - box_x + 1.0, hit.y() + 1.0);  // its own pattern, moving with it
        f.depth.at<float>(v, u) = static_cast<float>(t_box);
      } else {
        const double t_wall = 3.0 - centre.z();
        const Eigen::Vector3d wall = centre + t_wall * ray;
        value = texture(wall.x(), wall.y());
        f.depth.at<float>(v, u) = static_cast<float>(t_wall);
      }
      f.gray.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>(value);
    }
  return f;
}

// Superpixels and clusters: 40 x 40 px blocks (test_scenes.h: blockLabels).

// The box's pixels in the current view (its face, 0.05 m inside its edges so that LK windows stay on it).
inline bool onBoxInside(const core::PinholeCamera& camera, const Eigen::Vector3d& centre, double box_x, cv::Point2f p) {
  const Eigen::Vector3d hit = centre + (1.5 - centre.z()) * camera.backProject(p.x, p.y, 1.0);
  return std::abs(hit.x() - box_x) <= 0.25 && std::abs(hit.y()) <= 0.25;
}

// The wall's pixels more than 0.1 m (at the box's depth) away from the box's edges.
inline bool awayFromBox(const core::PinholeCamera& camera, const Eigen::Vector3d& centre, cv::Point2f p) {
  const Eigen::Vector3d hit = centre + (1.5 - centre.z()) * camera.backProject(p.x, p.y, 1.0);
  return std::abs(hit.x()) > 0.4 || std::abs(hit.y()) > 0.4;
}

struct Scene {
  core::PinholeCamera camera = testing::testCamera();
  DynamicOptions options;
  // The baseline frame 10 frames back: the camera 4 cm to the left and 2 cm back; the box at x = box_before.
  Eigen::Vector3d c_before{-0.04, 0.0, -0.02}, c_now{0.0, 0.0, 0.0};

  BaselineMotion motion(double box_before, double box_now, const core::SE3& baseline_pose_error = core::SE3::Identity(),
                        std::vector<cv::Point2f>* corners_out = nullptr) const {
    const Frame before = render(camera, c_before, box_before), now = render(camera, c_now, box_now);
    const std::vector<cv::Point2f> corners = detectCorners(now.gray, options.tracking);
    if (corners_out) *corners_out = corners;
    const core::SE3 T_cw_now = poseAt(c_now), T_cw_before = baseline_pose_error * poseAt(c_before);
    const BaselineImages frames{now.gray, now.depth, T_cw_now, before.gray, T_cw_before};
    return baselineMotion(corners, frames, camera, options);
  }
};

}  // namespace amos::evidence::box_wall
