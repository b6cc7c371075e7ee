#include "amos/geometry/photometric_alignment.h"

#include <opencv2/imgproc.hpp>
#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "amos/core/error.h"
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

namespace {

StereoProjection atLevel(const StereoProjection& k, int level) {
  const double s = 1.0 / (1 << level);
  // pyrDown halves the image about pixel centres: x_l = (x_0 + 0.5) / 2^l - 0.5.
  return {k.fx * s, k.fy * s, (k.cx + 0.5) * s - 0.5, (k.cy + 0.5) * s - 0.5, k.bf * s};
}

// Bilinear value and central-difference gradient of a CV_8U or CV_32F image at (u, v); false near the border.
template <typename T>
bool sampleAs(const cv::Mat& img, double u, double v, double& value, double& gx, double& gy) {
  if (u < 1 || v < 1 || u >= img.cols - 2 || v >= img.rows - 2) return false;
  const int x = static_cast<int>(u), y = static_cast<int>(v);
  const double fx = u - x, fy = v - y;
  auto at = [&](int r, int c) { return static_cast<double>(img.at<T>(r, c)); };
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

bool sample(const cv::Mat& img, double u, double v, double& value, double& gx, double& gy) {
  return img.depth() == CV_8U ? sampleAs<std::uint8_t>(img, u, v, value, gx, gy)
                              : sampleAs<float>(img, u, v, value, gx, gy);
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
  const core::RadialTangential* lens;  // nullptr: no distortion, the pinhole expressions exactly
  double max_r2;
  double huber_k = 1.345;
  double a = 1, b = 0, sigma = 1;
};

// The photometric residual of one point at pose T_cr; false when it leaves the image or falls in the mask.
bool photometricResidual(const LevelState& s, const PhotometricPoint& pt, const core::SE3& T_cr, double& r,
                         Eigen::Matrix<double, 1, 6>* J) {
  const Eigen::Vector3d pc = T_cr * pt.p_r;
  if (pc.z() <= 0.05) return false;
  const double iz = 1.0 / pc.z();
  double u, v;
  Eigen::Matrix2d J_lens;  // d(distorted) / d(normalised)
  if (s.lens) {
    const Eigen::Vector2d xn(pc.x() * iz, pc.y() * iz);
    if (xn.squaredNorm() > s.max_r2) return false;
    const Eigen::Vector2d xd = s.lens->distort(xn, J ? &J_lens : nullptr);
    u = s.k.fx * xd.x() + s.k.cx;
    v = s.k.fy * xd.y() + s.k.cy;
  } else {
    u = s.k.fx * pc.x() * iz + s.k.cx;
    v = s.k.fy * pc.y() * iz + s.k.cy;
  }
  double value, gx, gy;
  if (!sample(*s.gray, u, v, value, gx, gy)) return false;
  if (s.mask->at<std::uint8_t>(cvRound(v), cvRound(u)) != 0) return false;
  r = value - (s.a * pt.intensity + s.b);
  if (J) {
    Eigen::RowVector3d dr_dp;
    if (s.lens) {
      // dr/dxn = (gx fx, gy fy) J_lens; dxn/dp = (1/z, 0, -x/z^2; 0, 1/z, -y/z^2).
      const double a = gx * s.k.fx, b = gy * s.k.fy;
      const double wx = a * J_lens(0, 0) + b * J_lens(1, 0), wy = a * J_lens(0, 1) + b * J_lens(1, 1);
      dr_dp << wx * iz, wy * iz, -(wx * pc.x() + wy * pc.y()) * iz * iz;
    } else {
      const double du_x = s.k.fx * iz, du_z = -s.k.fx * pc.x() * iz * iz;
      const double dv_y = s.k.fy * iz, dv_z = -s.k.fy * pc.y() * iz * iz;
      dr_dp << gx * du_x, gy * dv_y, gx * du_z + gy * dv_z;
    }
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
                                      const core::RadialTangential& lens, const PhotometricOptions& options) {
  PhotometricImage out;
  makePhotometricImage(gray, mask, camera, lens, options, out);
  return out;
}

namespace {

// The largest squared radius of undistorted normalised coordinates over the image's border (corners and edge
// middles: with barrel or pincushion distortion the extreme lies at one of them).
double maxRadius2(const StereoProjection& k, const core::RadialTangential& lens, cv::Size size) {
  const double w = size.width - 1, h = size.height - 1;
  const std::pair<double, double> border[] = {{0, 0}, {w, 0}, {0, h}, {w, h}, {w / 2, 0}, {w / 2, h}, {0, h / 2},
                                              {w, h / 2}};
  double r2 = 0;
  for (const auto& [u, v] : border) {
    r2 = std::max(r2, lens.undistort({(u - k.cx) / k.fx, (v - k.cy) / k.fy}).squaredNorm());
  }
  return r2;
}

}  // namespace

void makePhotometricImage(const cv::Mat& gray, const cv::Mat& mask, const StereoProjection& camera,
                          const core::RadialTangential& lens, const PhotometricOptions& options,
                          PhotometricImage& out) {
  core::require(gray.type() == CV_8UC1, "makePhotometricImage: the grey image must be CV_8UC1");
  const auto levels = static_cast<std::size_t>(options.levels);
  out.gray.resize(levels);
  out.mask.resize(levels);
  out.intrinsics.resize(levels);
  out.gray[0] = gray;
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
  out.lens = lens;
  out.max_r2 = lens.none() ? std::numeric_limits<double>::infinity() : maxRadius2(camera, lens, gray.size());
  if (levels > 1) gray.convertTo(out.scratch_float, CV_32F);  // the pyramid is smoothed in float, as before
  for (std::size_t l = 1; l < levels; ++l) {
    cv::pyrDown(l == 1 ? out.scratch_float : out.gray[l - 1], out.gray[l]);
    // A coarse pixel is excluded when any of the fine pixels under it is.
    cv::dilate(out.mask[l - 1], out.scratch, cv::Mat::ones(3, 3, CV_8U));
    cv::resize(out.scratch, out.mask[l], out.gray[l].size(), 0, 0, cv::INTER_NEAREST);
    out.intrinsics[l] = atLevel(camera, static_cast<int>(l));
  }
}

namespace {

// Selects level l's template points (see makePhotometricTemplate) from its grey image of pixel type T.
template <typename T>
void selectPoints(const PhotometricImage& image, int l, const cv::Mat& depth, const PhotometricOptions& options,
                  std::vector<PhotometricPoint>& out) {
  const cv::Mat& g = image.gray[l];
  const cv::Mat& m = image.mask[l];
  const StereoProjection& k = image.intrinsics[l];
  const int cell = std::max(2, options.cell >> l);
  const int scale = 1 << l;
  for (int cy = 2; cy + cell <= g.rows - 2; cy += cell) {
    for (int cx = 2; cx + cell <= g.cols - 2; cx += cell) {
      double best = options.min_gradient * options.min_gradient;
      int bx = -1, by = -1;
      float bz = 0;
      for (int y = cy; y < cy + cell; ++y) {
        for (int x = cx; x < cx + cell; ++x) {
          if (m.at<std::uint8_t>(y, x) != 0) continue;
          const double gx = 0.5 * (g.at<T>(y, x + 1) - g.at<T>(y, x - 1));
          const double gy = 0.5 * (g.at<T>(y + 1, x) - g.at<T>(y - 1, x));
          const double g2 = gx * gx + gy * gy;
          if (g2 <= best) continue;
          // The depth at the same raw pixel (its level-0 centre).
          const int x0 = std::clamp(x * scale + scale / 2, 1, depth.cols - 2);
          const int y0 = std::clamp(y * scale + scale / 2, 1, depth.rows - 2);
          const float z = depth.at<float>(y0, x0);
          if (!(z >= options.min_depth && z <= options.max_depth)) continue;
          cv::Mat block = depth(cv::Rect(x0 - 1, y0 - 1, 3, 3));
          double lo, hi;
          cv::minMaxLoc(block, &lo, &hi);
          if (lo <= 0 || hi - lo > options.depth_edge * z) continue;
          best = g2;
          bx = x;
          by = y;
          bz = z;
        }
      }
      if (bx < 0) continue;
      PhotometricPoint chosen;
      if (image.lens.none()) {
        chosen.p_r = {(bx - k.cx) * bz / k.fx, (by - k.cy) * bz / k.fy, bz};
      } else {
        // Along the undistorted ray of the raw pixel: reprojected through the lens it lands on that pixel.
        const Eigen::Vector2d xn = image.lens.undistort({(bx - k.cx) / k.fx, (by - k.cy) / k.fy});
        chosen.p_r = {xn.x() * bz, xn.y() * bz, bz};
      }
      chosen.intensity = g.at<T>(by, bx);
      out.push_back(chosen);
    }
  }
}

}  // namespace

PhotometricTemplate makePhotometricTemplate(const PhotometricImage& image, const cv::Mat& depth,
                                            const PhotometricOptions& options) {
  core::require(depth.type() == CV_32FC1 && depth.size() == image.gray.front().size(),
                "makePhotometricTemplate: the depth must be CV_32FC1, registered to the grey image");
  PhotometricTemplate out;
  out.levels.resize(image.levels());
  for (int l = 0; l < image.levels(); ++l) {
    if (image.gray[l].depth() == CV_8U) {
      selectPoints<std::uint8_t>(image, l, depth, options, out.levels[l]);
    } else {
      selectPoints<float>(image, l, depth, options, out.levels[l]);
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
    const PhotometricImage& c = *p.current;
    LevelState s{&p.reference->levels[l], &c.gray[l], &c.mask[l], c.intrinsics[l], c.lens.none() ? nullptr : &c.lens,
                 c.max_r2, o.huber_k};
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
