#include "amos/geometry/photometric_alignment.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

#include "amos/core/option_error.h"

namespace amos::geometry {

void PhotometricOptions::check() const {
  core::requireAtLeast(levels, "levels", 1);
  core::requireAtLeast(cell, "cell", 1);
  core::requireAtLeast(min_gradient, "min_gradient", 0.0);
  core::requirePositive(min_depth, "min_depth");
  core::requireAtLeast(max_depth, "max_depth", min_depth);
  core::requirePositive(depth_edge, "depth_edge");
  core::requireAtLeast(mask_margin, "mask_margin", 0);
  core::requireAtLeast(iterations, "iterations", 1);
  core::requirePositive(huber_k, "huber_k");
  core::requireAtLeast(min_points, "min_points", 1);
}

ImageRectifier::ImageRectifier(const core::PinholeCamera& camera) {
  identity_ = !camera.intrinsics().hasDistortion();
  if (identity_) return;
  cv::Mat map_x, map_y;
  cv::initUndistortRectifyMap(camera.K(), camera.distortion(), cv::noArray(), camera.K(),
                              cv::Size(camera.width(), camera.height()), CV_32FC1, map_x, map_y);
  cv::convertMaps(map_x, map_y, linear_xy_, linear_a_, CV_16SC2, false);
  cv::Mat unused;
  cv::convertMaps(map_x, map_y, nearest_xy_, unused, CV_16SC2, true);
}

cv::Mat ImageRectifier::linear(const cv::Mat& image) const {
  cv::Mat out;
  linear(image, out);
  return out;
}

cv::Mat ImageRectifier::nearest(const cv::Mat& image) const {
  cv::Mat out;
  nearest(image, out);
  return out;
}

void ImageRectifier::linear(const cv::Mat& image, cv::Mat& out) const {
  if (identity_) {
    out = image;
    return;
  }
  cv::remap(image, out, linear_xy_, linear_a_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
}

void ImageRectifier::nearest(const cv::Mat& image, cv::Mat& out) const {
  if (identity_) {
    out = image;
    return;
  }
  // Outside the source image: 0 (no depth) for depth; masks are made so that 0 there is handled by the caller.
  cv::remap(image, out, nearest_xy_, cv::noArray(), cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
}

namespace {

StereoProjection atLevel(const StereoProjection& k, int level) {
  const double s = 1.0 / (1 << level);
  // pyrDown halves the image about pixel centres: x_l = (x_0 + 0.5) / 2^l - 0.5.
  return {k.fx * s, k.fy * s, (k.cx + 0.5) * s - 0.5, (k.cy + 0.5) * s - 0.5, k.bf * s};
}

// Bilinear value and central-difference gradient of a CV_32F image at (u, v); false near the border.
bool sample(const cv::Mat& img, double u, double v, double& value, double& gx, double& gy) {
  if (u < 1 || v < 1 || u >= img.cols - 2 || v >= img.rows - 2) return false;
  const int x = static_cast<int>(u), y = static_cast<int>(v);
  const double fx = u - x, fy = v - y;
  auto at = [&](int r, int c) { return static_cast<double>(img.at<float>(r, c)); };
  auto bil = [&](int r, int c) {
    return (1 - fy) * ((1 - fx) * at(r, c) + fx * at(r, c + 1)) + fy * ((1 - fx) * at(r + 1, c) + fx * at(r + 1, c + 1));
  };
  value = bil(y, x);
  // Gradient: bilinear interpolation of the central differences at the four neighbours.
  auto dx = [&](int r, int c) { return 0.5 * (at(r, c + 1) - at(r, c - 1)); };
  auto dy = [&](int r, int c) { return 0.5 * (at(r + 1, c) - at(r - 1, c)); };
  gx = (1 - fy) * ((1 - fx) * dx(y, x) + fx * dx(y, x + 1)) + fy * ((1 - fx) * dx(y + 1, x) + fx * dx(y + 1, x + 1));
  gy = (1 - fy) * ((1 - fx) * dy(y, x) + fx * dy(y, x + 1)) + fy * ((1 - fx) * dy(y + 1, x) + fx * dy(y + 1, x + 1));
  return true;
}

double huberCost(double e, double k) {
  const double a = std::abs(e);
  return a <= k ? 0.5 * e * e : k * a - 0.5 * k * k;
}

double huberWeight(double e, double k) {
  const double a = std::abs(e);
  return a <= k ? 1.0 : k / a;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

using Matrix6 = Eigen::Matrix<double, 6, 6>;

// The feature terms: 0.5 * sum r^T W r over the inliers, its Gauss-Newton Hessian and gradient.
double featureTerms(const PhotometricProblem& p, const core::SE3& T, Matrix6* H, core::Vector6d* g) {
  double cost = 0;
  Eigen::Vector3d r;
  Eigen::Matrix<double, 3, 6> J;
  for (const PoseObservation& obs : *p.features) {
    if (!poseObservationJacobian(obs, T, p.projection, r, J)) continue;
    const int rows = obs.u_right >= 0 ? 3 : 2;
    cost += 0.5 * obs.inv_sigma2 * r.head(rows).squaredNorm();
    if (!H) continue;
    *H += obs.inv_sigma2 * J.topRows(rows).transpose() * J.topRows(rows);
    *g += obs.inv_sigma2 * J.topRows(rows).transpose() * r.head(rows);
  }
  return cost;
}

struct LevelState {
  const std::vector<PhotometricPoint>* points;
  const cv::Mat* gray;
  const cv::Mat* mask;
  StereoProjection k;
  double huber_k = 1.345;
  double a = 1, b = 0, sigma = 1;
};

// The photometric residual of one point at pose T_cr; false when it leaves the image or falls in the mask.
bool photometricResidual(const LevelState& s, const PhotometricPoint& pt, const core::SE3& T_cr, double& r,
                         Eigen::Matrix<double, 1, 6>* J) {
  const Eigen::Vector3d pc = T_cr * pt.p_r;
  if (pc.z() <= 0.05) return false;
  const double iz = 1.0 / pc.z();
  const double u = s.k.fx * pc.x() * iz + s.k.cx, v = s.k.fy * pc.y() * iz + s.k.cy;
  double value, gx, gy;
  if (!sample(*s.gray, u, v, value, gx, gy)) return false;
  if (s.mask->at<std::uint8_t>(cvRound(v), cvRound(u)) != 0) return false;
  r = value - (s.a * pt.intensity + s.b);
  if (J) {
    const double du_x = s.k.fx * iz, du_z = -s.k.fx * pc.x() * iz * iz;
    const double dv_y = s.k.fy * iz, dv_z = -s.k.fy * pc.y() * iz * iz;
    const Eigen::RowVector3d dr_dp(gx * du_x, gy * dv_y, gx * du_z + gy * dv_z);
    (*J).leftCols<3>() = dr_dp;
    (*J).rightCols<3>() = -dr_dp * core::skew(pc);
  }
  return true;
}

// Robust photometric cost (points that left the view cost as a residual at the Huber threshold's double).
double photometricTerms(const LevelState& s, const core::SE3& T_cr, Matrix6* H, core::Vector6d* g,
                        int* used = nullptr) {
  double cost = 0;
  int n = 0;
  Eigen::Matrix<double, 1, 6> J;
  for (const PhotometricPoint& pt : *s.points) {
    double r;
    if (!photometricResidual(s, pt, T_cr, r, H ? &J : nullptr)) {
      cost += huberCost(2 * s.huber_k, s.huber_k);
      continue;
    }
    ++n;
    const double e = r / s.sigma;
    cost += huberCost(e, s.huber_k);
    if (!H) continue;
    const double w = huberWeight(e, s.huber_k) / (s.sigma * s.sigma);
    *H += w * J.transpose() * J;
    *g += w * J.transpose() * r;
  }
  if (used) *used = n;
  return cost;
}

// Fits the reference's affine brightness (a, b) and the robust scale sigma at pose T_cr (iteratively reweighted
// least squares with the Huber kernel); false when too few points are visible.
bool fitBrightness(LevelState& s, const core::SE3& T_cr, int min_points) {
  std::vector<double> ic, ir;
  ic.reserve(s.points->size());
  ir.reserve(s.points->size());
  const double a0 = s.a, b0 = s.b;
  s.a = 1;
  s.b = 0;
  for (const PhotometricPoint& pt : *s.points) {
    double r;
    if (!photometricResidual(s, pt, T_cr, r, nullptr)) continue;
    ic.push_back(r + pt.intensity);  // with a = 1, b = 0: r = I_c - I_r
    ir.push_back(pt.intensity);
  }
  if (static_cast<int>(ic.size()) < min_points) {
    s.a = a0;
    s.b = b0;
    return false;
  }
  std::vector<double> d(ic.size());
  for (std::size_t i = 0; i < ic.size(); ++i) d[i] = ic[i] - ir[i];
  s.a = 1;
  s.b = median(d);
  for (int pass = 0; pass < 3; ++pass) {
    for (std::size_t i = 0; i < ic.size(); ++i) d[i] = std::abs(ic[i] - s.a * ir[i] - s.b);
    s.sigma = std::max(1.4826 * median(d), 1.0);
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < ic.size(); ++i) {
      const double w = huberWeight((ic[i] - s.a * ir[i] - s.b) / s.sigma, s.huber_k);
      sw += w;
      sx += w * ir[i];
      sy += w * ic[i];
      sxx += w * ir[i] * ir[i];
      sxy += w * ir[i] * ic[i];
    }
    const double det = sw * sxx - sx * sx;
    if (std::abs(det) < 1e-9) break;
    s.a = std::clamp((sw * sxy - sx * sy) / det, 0.5, 2.0);
    s.b = (sy - s.a * sx) / sw;
  }
  for (std::size_t i = 0; i < ic.size(); ++i) d[i] = std::abs(ic[i] - s.a * ir[i] - s.b);
  s.sigma = std::max(1.4826 * median(d), 1.0);
  return true;
}

}  // namespace

PhotometricImage makePhotometricImage(const cv::Mat& gray, const cv::Mat& mask, const StereoProjection& camera,
                                      const PhotometricOptions& options) {
  PhotometricImage out;
  makePhotometricImage(gray, mask, camera, options, out);
  return out;
}

void makePhotometricImage(const cv::Mat& gray, const cv::Mat& mask, const StereoProjection& camera,
                          const PhotometricOptions& options, PhotometricImage& out) {
  const auto levels = static_cast<std::size_t>(options.levels);
  out.gray.resize(levels);
  out.mask.resize(levels);
  out.intrinsics.resize(levels);
  gray.convertTo(out.gray[0], CV_32F);
  if (mask.empty()) {
    out.mask[0].create(gray.size(), CV_8U);
    out.mask[0].setTo(0);
  } else if (options.mask_margin > 0) {
    const int d = 2 * options.mask_margin + 1;
    cv::dilate(mask, out.mask[0], cv::getStructuringElement(cv::MORPH_RECT, cv::Size(d, d)));
  } else {
    mask.copyTo(out.mask[0]);
  }
  out.intrinsics[0] = camera;
  for (std::size_t l = 1; l < levels; ++l) {
    cv::pyrDown(out.gray[l - 1], out.gray[l]);
    // A coarse pixel is excluded when any of the fine pixels under it is.
    cv::dilate(out.mask[l - 1], out.scratch, cv::Mat::ones(3, 3, CV_8U));
    cv::resize(out.scratch, out.mask[l], out.gray[l].size(), 0, 0, cv::INTER_NEAREST);
    out.intrinsics[l] = atLevel(camera, static_cast<int>(l));
  }
}

PhotometricTemplate makePhotometricTemplate(const PhotometricImage& image, const cv::Mat& depth,
                                            const PhotometricOptions& options) {
  PhotometricTemplate out;
  out.levels.resize(image.levels());
  for (int l = 0; l < image.levels(); ++l) {
    const cv::Mat& g = image.gray[l];
    const cv::Mat& m = image.mask[l];
    const StereoProjection& k = image.intrinsics[l];
    const int cell = std::max(2, options.cell >> l);
    const int scale = 1 << l;
    for (int cy = 2; cy + cell <= g.rows - 2; cy += cell) {
      for (int cx = 2; cx + cell <= g.cols - 2; cx += cell) {
        double best = options.min_gradient * options.min_gradient;
        PhotometricPoint chosen;
        bool found = false;
        for (int y = cy; y < cy + cell; ++y) {
          for (int x = cx; x < cx + cell; ++x) {
            if (m.at<std::uint8_t>(y, x) != 0) continue;
            const double gx = 0.5 * (g.at<float>(y, x + 1) - g.at<float>(y, x - 1));
            const double gy = 0.5 * (g.at<float>(y + 1, x) - g.at<float>(y - 1, x));
            const double g2 = gx * gx + gy * gy;
            if (g2 <= best) continue;
            const int x0 = std::clamp(x * scale + scale / 2, 1, depth.cols - 2);
            const int y0 = std::clamp(y * scale + scale / 2, 1, depth.rows - 2);
            const float z = depth.at<float>(y0, x0);
            if (!(z >= options.min_depth && z <= options.max_depth)) continue;
            cv::Mat block = depth(cv::Rect(x0 - 1, y0 - 1, 3, 3));
            double lo, hi;
            cv::minMaxLoc(block, &lo, &hi);
            if (lo <= 0 || hi - lo > options.depth_edge * z) continue;
            best = g2;
            chosen.p_r = {(x - k.cx) * z / k.fx, (y - k.cy) * z / k.fy, z};
            chosen.intensity = g.at<float>(y, x);
            found = true;
          }
        }
        if (found) out.levels[l].push_back(chosen);
      }
    }
  }
  return out;
}

PhotometricResult refinePosePhotometrically(const PhotometricProblem& p, const core::SE3& initial_T_cw,
                                            const PhotometricOptions& o) {
  PhotometricResult result;
  result.T_cw = initial_T_cw;
  const int levels = std::min(p.current->levels(), static_cast<int>(p.reference->levels.size()));
  const core::SE3 T_wr = p.T_rw.inverse();
  core::SE3 T = initial_T_cw;
  bool refined_finest = false;
  for (int l = levels - 1; l >= 0; --l) {
    LevelState s{&p.reference->levels[l], &p.current->gray[l], &p.current->mask[l], p.current->intrinsics[l],
                 o.huber_k};
    if (!fitBrightness(s, T * T_wr, o.min_points)) continue;
    // Gauss-Newton; each iteration's evaluation also checks the step before it (a step that raised the joint
    // cost is taken back and the level ends), so the data are visited once per iteration.
    core::SE3 previous = T;
    double previous_cost = std::numeric_limits<double>::infinity();
    for (int it = 0; it < o.iterations; ++it) {
      Matrix6 H = Matrix6::Zero();
      core::Vector6d g = core::Vector6d::Zero();
      const double cost = featureTerms(p, T, &H, &g) + photometricTerms(s, T * T_wr, &H, &g);
      if (cost >= previous_cost) {
        T = previous;
        break;
      }
      previous = T;
      previous_cost = cost;
      const core::Vector6d delta = H.ldlt().solve(-g);
      if (!delta.allFinite()) break;
      T = core::expSE3(delta) * T;
      // 0.03 mm and 0.002 deg: a tenth of the one-frame error left on exact synthetic renders.
      if (delta.squaredNorm() < 1e-9) break;
    }
    if (l == 0) {
      refined_finest = true;
      core::Vector6d unused = core::Vector6d::Zero();
      photometricTerms(s, T * T_wr, &result.information, &unused, &result.points);
      result.sigma = s.sigma;
    }
  }
  if (!refined_finest) return result;
  result.T_cw = T;
  result.accepted = true;
  return result;
}

}  // namespace amos::geometry
