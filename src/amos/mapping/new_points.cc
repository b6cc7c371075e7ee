#include "amos/mapping/new_points.h"

#include <fmt/format.h>
#include <cmath>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/feature/descriptor_distance.h"
#include "amos/geometry/triangulation.h"
#include "amos/mapping/epipolar_band.h"
#include "amos/match/rotation_consistency.h"

namespace amos::mapping {

void NewPointsOptions::check() const {
  core::requireAtLeast(neighbors, "neighbors", 1);
  core::requireOption(max_distance > 0 && max_distance <= 256, core::option(max_distance, "max_distance"),
                      fmt::format("must be in (0, 256], got {}", max_distance));
  core::requireOption(ratio > 0 && ratio <= 1, core::option(ratio, "ratio"),
                      fmt::format("must be in (0, 1], got {}", ratio));
  core::requireOption(max_cos_parallax > 0 && max_cos_parallax < 1, core::option(max_cos_parallax, "max_cos_parallax"),
                      fmt::format("must be in (0, 1), got {}", max_cos_parallax));
}

namespace {

// Reprojection test of a world point in a keyframe keypoint (chi-square, with u_r when there is depth).
bool reprojects(const map::KeyFrame& kf, int idx, const Eigen::Vector3d& pw, const core::SE3& T_cw) {
  const Eigen::Vector3d pc = T_cw * pw;
  if (pc.z() <= 0) return false;
  const map::Sensor& s = kf.sensor();
  const cv::KeyPoint& kp = kf.features().keys[idx];
  const double inv_z = 1.0 / pc.z();
  const double u = s.camera().fx() * pc.x() * inv_z + s.camera().cx();
  const double v = s.camera().fy() * pc.y() * inv_z + s.camera().cy();
  const double sigma2 = s.sigma2()[kp.octave];
  const double ex = u - kp.pt.x, ey = v - kp.pt.y;
  const float ur = kf.features().u_right[idx];
  if (ur < 0) return (ex * ex + ey * ey) < 5.991 * sigma2;
  const double er = u - s.bf() * inv_z - ur;
  return (ex * ex + ey * ey + er * er) < 7.815 * sigma2;
}

// kf2's keypoints without a map point, in index order: where they are, with the chi-square bound of the epipolar
// test (3.84 sigma^2 of the keypoint's octave: 1 dof, 95 %), and whether they are too near kf1's epipole (no depth
// and within 10 scale-pixels of it).
struct FreeKeypoints {
  std::vector<int> index;
  std::vector<char> near_epipole;
  EpipolarBand band;
};

FreeKeypoints freeKeypoints(const map::KeyFrame& kf, double epipole_u, double epipole_v) {
  const map::Sensor& s = kf.sensor();
  const map::FrameFeatures& f = kf.features();
  std::vector<int> index;
  std::vector<char> near_epipole;
  std::vector<BandPoint> points;
  for (int i = 0; i < kf.size(); ++i) {
    if (kf.mapPoint(i)) continue;
    const cv::KeyPoint& kp = f.keys[i];
    const double dx = epipole_u - kp.pt.x, dy = epipole_v - kp.pt.y;
    index.push_back(i);
    near_epipole.push_back(f.u_right[i] < 0 && dx * dx + dy * dy < 100 * s.scales()[kp.octave]);
    points.push_back({kp.pt.x, kp.pt.y, 3.84 * s.sigma2()[kp.octave]});
  }
  return {std::move(index), std::move(near_epipole), EpipolarBand(std::move(points))};
}

}  // namespace

std::vector<NewPointCandidate> findNewPoints(const map::Map& map, const map::KeyFramePtr& kf1,
                                             const NewPointsOptions& options) {
  std::vector<NewPointCandidate> out;
  const map::Sensor& s = kf1->sensor();
  const map::FrameFeatures& f1 = kf1->features();
  const core::SE3 T1 = kf1->T_cw();
  const Eigen::Vector3d O1 = kf1->center();
  const Eigen::Matrix3d K = s.camera().eigenK();
  const Eigen::Matrix3d Kinv = K.inverse();
  const double ratio_factor = 1.5 * s.scaleFactor();
  std::vector<int> free1;
  for (int i = 0; i < kf1->size(); ++i) {
    if (!kf1->mapPoint(i)) free1.push_back(i);
  }
  // A keypoint of kf1 gets at most one new point (the first neighbour that triangulates it wins).
  std::vector<bool> used1(kf1->size(), false);
  std::vector<int> on_line;  // free2 slots near the current epipolar line

  for (const map::KeyFrameId nid : kf1->bestCovisibles(options.neighbors)) {
    const map::KeyFramePtr kf2 = map.keyFrame(nid);
    if (!kf2 || kf2->isBad()) continue;
    const Eigen::Vector3d O2 = kf2->center();
    if ((O2 - O1).norm() < s.baseline()) continue;  // RGB-D: depth already covers such short baselines
    const core::SE3 T2 = kf2->T_cw();
    const map::FrameFeatures& f2 = kf2->features();
    // Fundamental matrix F12 with x1^T F12 x2 = 0.
    const core::SE3 T12 = T1 * T2.inverse();
    const Eigen::Matrix3d F12 = Kinv.transpose() * core::skew(T12.translation()) * T12.linear() * Kinv;
    // Epipole of camera 1 in image 2.
    const Eigen::Vector3d c1_in_2 = T2 * O1;
    const double ex = s.camera().fx() * c1_in_2.x() / c1_in_2.z() + s.camera().cx();
    const double ey = s.camera().fy() * c1_in_2.y() / c1_in_2.z() + s.camera().cy();
    const FreeKeypoints free2 = freeKeypoints(*kf2, ex, ey);
    std::vector<int> match12(kf1->size(), -1);
    std::vector<int> taken2(kf2->size(), -1);  // best kf1 index per kf2 keypoint
    std::vector<int> taken2_dist(kf2->size(), 257);
    for (const int i1 : free1) {
      if (used1[i1]) continue;
      const cv::KeyPoint& kp1 = f1.keys[i1];
      const bool stereo1 = f1.u_right[i1] >= 0;
      const double a = kp1.pt.x * F12(0, 0) + kp1.pt.y * F12(1, 0) + F12(2, 0);
      const double b = kp1.pt.x * F12(0, 1) + kp1.pt.y * F12(1, 1) + F12(2, 1);
      const double c = kp1.pt.x * F12(0, 2) + kp1.pt.y * F12(1, 2) + F12(2, 2);
      free2.band.near(a, b, c, on_line);  // none for a degenerate line (a = b = 0)
      const std::uint8_t* d1 = f1.descriptors.ptr<std::uint8_t>(i1);
      int best = 257, second = 257, best_i2 = -1;
      for (const int k : on_line) {
        if (!stereo1 && free2.near_epipole[static_cast<size_t>(k)]) continue;  // too close to the epipole
        const int i2 = free2.index[static_cast<size_t>(k)];
        const int dist = feature::hammingDistance(d1, f2.descriptors.ptr<std::uint8_t>(i2));
        if (dist < best) {
          second = best;
          best = dist;
          best_i2 = i2;
        } else if (dist < second) {
          second = dist;
        }
      }
      if (best_i2 < 0 || best > options.max_distance || best > options.ratio * second) continue;
      if (best < taken2_dist[best_i2]) {
        if (taken2[best_i2] >= 0) match12[taken2[best_i2]] = -1;
        taken2[best_i2] = i1;
        taken2_dist[best_i2] = best;
        match12[i1] = best_i2;
      }
    }
    std::vector<int> idx1s;
    std::vector<float> rot;
    for (int i1 = 0; i1 < kf1->size(); ++i1) {
      if (match12[i1] < 0) continue;
      idx1s.push_back(i1);
      rot.push_back(f1.keys[i1].angle - f2.keys[match12[i1]].angle);
    }
    const std::vector<bool> keep =
        options.check_orientation ? match::rotationConsistent(rot) : std::vector<bool>(idx1s.size(), true);

    for (std::size_t k = 0; k < idx1s.size(); ++k) {
      if (!keep[k]) continue;
      const int i1 = idx1s[k], i2 = match12[i1];
      const cv::KeyPoint& kp1 = f1.keys[i1];
      const cv::KeyPoint& kp2 = f2.keys[i2];
      const bool stereo1 = f1.u_right[i1] >= 0, stereo2 = f2.u_right[i2] >= 0;
      const Eigen::Vector3d xn1 = Kinv * Eigen::Vector3d(kp1.pt.x, kp1.pt.y, 1);
      const Eigen::Vector3d xn2 = Kinv * Eigen::Vector3d(kp2.pt.x, kp2.pt.y, 1);
      const Eigen::Vector3d ray1 = T1.linear().transpose() * xn1;
      const Eigen::Vector3d ray2 = T2.linear().transpose() * xn2;
      const double cos_rays = ray1.dot(ray2) / (ray1.norm() * ray2.norm());
      double cos_stereo1 = 2, cos_stereo2 = 2;
      if (stereo1) cos_stereo1 = std::cos(2 * std::atan2(s.baseline() / 2, f1.depth[i1]));
      if (stereo2) cos_stereo2 = std::cos(2 * std::atan2(s.baseline() / 2, f2.depth[i2]));
      const double cos_stereo = std::min(cos_stereo1, cos_stereo2);
      Eigen::Vector3d pw;
      if (cos_rays < cos_stereo && cos_rays > 0 && (stereo1 || stereo2 || cos_rays < options.max_cos_parallax)) {
        const auto X = geometry::triangulateDlt(xn1.head<2>(), T1, xn2.head<2>(), T2);
        if (!X) continue;
        pw = *X;
      } else if (stereo1 && cos_stereo1 < cos_stereo2) {
        pw = T1.inverse() * s.camera().backProject(kp1.pt.x, kp1.pt.y, f1.depth[i1]);
      } else if (stereo2 && cos_stereo2 < cos_stereo1) {
        pw = T2.inverse() * s.camera().backProject(kp2.pt.x, kp2.pt.y, f2.depth[i2]);
      } else {
        continue;  // no parallax
      }
      if (!reprojects(*kf1, i1, pw, T1) || !reprojects(*kf2, i2, pw, T2)) continue;
      const double dist1 = (pw - O1).norm(), dist2 = (pw - O2).norm();
      if (dist1 <= 0 || dist2 <= 0) continue;
      const double ratio_dist = dist2 / dist1;
      const double ratio_octave = s.scales()[kp1.octave] / s.scales()[kp2.octave];
      if (ratio_dist * ratio_factor < ratio_octave || ratio_dist > ratio_octave * ratio_factor) continue;
      out.push_back({pw, kf1->id(), kf2->id(), i1, i2});
      used1[i1] = true;
    }
  }
  return out;
}

std::vector<map::MapPointPtr> addNewPoints(map::Map& map, const std::vector<NewPointCandidate>& candidates,
                                           map::FrameId frame) {
  std::vector<map::MapPointPtr> out;
  for (const auto& c : candidates) {
    const map::KeyFramePtr kf1 = map.keyFrame(c.kf1), kf2 = map.keyFrame(c.kf2);
    if (!kf1 || !kf2 || kf1->isBad() || kf2->isBad()) continue;
    if (kf1->mapPoint(c.idx1) || kf2->mapPoint(c.idx2)) continue;
    auto p = std::make_shared<map::MapPoint>(map.newMapPointId(), c.position, kf1->id(), frame);
    map.addObservation(p, kf1, c.idx1);
    map.addObservation(p, kf2, c.idx2);
    map.updateDescriptor(p);
    map.updateNormalAndDepth(p);
    map.addMapPoint(p);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace amos::mapping
