#include "amos/geometry/epnp.h"

#include <opencv2/calib3d.hpp>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>

namespace amos::geometry {

namespace {

using Vector10d = Eigen::Matrix<double, 10, 1>;
using Matrix6x10d = Eigen::Matrix<double, 6, 10>;
// The three beta approximations' least-squares systems (6 x 3, 4 or 5) share one QR type: one instantiation of
// Eigen's column-pivoting QR instead of three fixed-size ones (a third of this file's compile time), with no heap
// allocation (fixed maximum size).
using Matrix6xNd = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 5>;
using VectorNd = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 5, 1>;

// Least-squares solution of A x = rho.
VectorNd solveLeastSquares(const Matrix6xNd& A, const Eigen::Matrix<double, 6, 1>& rho) {
  return A.colPivHouseholderQr().solve(rho);
}
// Thickness (smallest / largest PCA variance) below which a point set counts as flat enough to also try SQPnP,
// and below which the four-control-point form is numerically singular.
constexpr double kTryPlanarRatio = 1e-2;
constexpr double kSingularRatio = 1e-10;
constexpr int kGaussNewtonIterations = 5;

// The six control-point pairs whose distances must be preserved.
constexpr std::array<std::array<int, 2>, 6> kPairs = {{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

// Monomials of the betas in the order the L matrix uses: b11 b12 b22 b13 b23 b33 b14 b24 b34 b44.
Vector10d monomials(const Eigen::Vector4d& b) {
  Vector10d m;
  m << b[0] * b[0], b[0] * b[1], b[1] * b[1], b[0] * b[2], b[1] * b[2], b[2] * b[2], b[0] * b[3], b[1] * b[3],
      b[2] * b[3], b[3] * b[3];
  return m;
}

// Rigid transform (R, t) with p_c = R p_w + t best aligning the two point sets (Horn / Umeyama, no scale).
core::SE3 alignRigid(const std::vector<Eigen::Vector3d>& pw, const std::vector<Eigen::Vector3d>& pc) {
  const size_t n = pw.size();
  Eigen::Vector3d mw = Eigen::Vector3d::Zero(), mc = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    mw += pw[i];
    mc += pc[i];
  }
  mw /= static_cast<double>(n);
  mc /= static_cast<double>(n);
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < n; ++i) H += (pc[i] - mc) * (pw[i] - mw).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  core::SE3 T = core::SE3::Identity();
  T.linear() = svd.matrixU() * D * svd.matrixV().transpose();
  T.translation() = mc - T.linear() * mw;
  return T;
}

double reprojectionError(const core::SE3& T, const std::vector<Eigen::Vector3d>& pw,
                         const std::vector<Eigen::Vector2d>& xy) {
  double e = 0;
  for (size_t i = 0; i < pw.size(); ++i) {
    const Eigen::Vector3d p = T * pw[i];
    if (p.z() <= 0) return std::numeric_limits<double>::infinity();
    e += (p.head<2>() / p.z() - xy[i]).squaredNorm();
  }
  return e;
}

class Epnp {
 public:
  Epnp(const std::vector<Eigen::Vector3d>& pw, const std::vector<Eigen::Vector2d>& xy) : pw_(pw), xy_(xy) {}

  // Control points and barycentric weights; returns the thickness ratio of the point set (0 when degenerate).
  double chooseControlPoints() {
    const size_t n = pw_.size();
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& p : pw_) centroid += p;
    centroid /= static_cast<double>(n);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : pw_) cov += (p - centroid) * (p - centroid).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(cov);
    const Eigen::Vector3d var = pca.eigenvalues();  // ascending
    if (!(var[2] > 0)) return 0;
    const double ratio = var[0] / var[2];
    if (ratio < kSingularRatio) return ratio;
    // Control points: the centroid and one point along each principal axis, at one standard deviation.
    cw_[0] = centroid;
    Eigen::Matrix3d axes;
    for (int j = 0; j < 3; ++j) {
      cw_[j + 1] = centroid + std::sqrt(var[2 - j] / static_cast<double>(n)) * pca.eigenvectors().col(2 - j);
      axes.col(j) = cw_[j + 1] - centroid;
    }
    const Eigen::Matrix3d inv = axes.inverse();
    alphas_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d a = inv * (pw_[i] - centroid);
      alphas_[i] = Eigen::Vector4d(1.0 - a.sum(), a[0], a[1], a[2]);
    }
    return ratio;
  }

  // Best of the three beta approximations (N = 1, 2, 3 null vectors, Gauss-Newton polished), if any.
  std::optional<core::SE3> solve() {
    // M^T M accumulated point by point: rows [a_j, 0, -a_j x] and [0, a_j, -a_j y] per control point j.
    Eigen::Matrix<double, 12, 12> MtM = Eigen::Matrix<double, 12, 12>::Zero();
    for (size_t i = 0; i < pw_.size(); ++i) {
      Eigen::Matrix<double, 12, 1> r1 = Eigen::Matrix<double, 12, 1>::Zero(), r2 = r1;
      for (int j = 0; j < 4; ++j) {
        const double a = alphas_[i][j];
        r1[3 * j] = a;
        r1[3 * j + 2] = -a * xy_[i].x();
        r2[3 * j + 1] = a;
        r2[3 * j + 2] = -a * xy_[i].y();
      }
      MtM.noalias() += r1 * r1.transpose() + r2 * r2.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eig(MtM);
    // Null vectors: eigenvectors of the four smallest eigenvalues, v_1 the smallest.
    for (int k = 0; k < 4; ++k) null_[k] = eig.eigenvectors().col(k);

    Matrix6x10d L;
    Eigen::Matrix<double, 6, 1> rho;
    for (int p = 0; p < 6; ++p) {
      const int a = kPairs[p][0], b = kPairs[p][1];
      std::array<Eigen::Vector3d, 4> dv;
      for (int k = 0; k < 4; ++k) dv[k] = null_[k].segment<3>(3 * a) - null_[k].segment<3>(3 * b);
      L.row(p) << dv[0].dot(dv[0]), 2 * dv[0].dot(dv[1]), dv[1].dot(dv[1]), 2 * dv[0].dot(dv[2]), 2 * dv[1].dot(dv[2]),
          dv[2].dot(dv[2]), 2 * dv[0].dot(dv[3]), 2 * dv[1].dot(dv[3]), 2 * dv[2].dot(dv[3]), dv[3].dot(dv[3]);
      rho[p] = (cw_[a] - cw_[b]).squaredNorm();
    }

    std::optional<core::SE3> best;
    double best_error = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector4d& initial : {approximation1(L, rho), approximation2(L, rho), approximation3(L, rho)}) {
      const Eigen::Vector4d betas = gaussNewton(L, rho, initial);
      if (!betas.allFinite()) continue;
      const std::optional<core::SE3> T = poseFromBetas(betas);
      if (!T) continue;
      const double e = reprojectionError(*T, pw_, xy_);
      if (e < best_error) {
        best_error = e;
        best = T;
      }
    }
    return best;
  }

 private:
  // N = 4 linearisation: [b11 b12 b13 b14] by least squares (columns 0, 1, 3, 6 of L).
  static Eigen::Vector4d approximation1(const Matrix6x10d& L, const Eigen::Matrix<double, 6, 1>& rho) {
    Matrix6xNd A(6, 4);
    A << L.col(0), L.col(1), L.col(3), L.col(6);
    const VectorNd b = solveLeastSquares(A, rho);
    const double b1 = std::sqrt(std::abs(b[0]));
    const double sign = b[0] < 0 ? -1.0 : 1.0;
    if (b1 == 0) return Eigen::Vector4d::Zero();
    return {b1, sign * b[1] / b1, sign * b[2] / b1, sign * b[3] / b1};
  }

  // N = 2: [b11 b12 b22] (columns 0, 1, 2).
  static Eigen::Vector4d approximation2(const Matrix6x10d& L, const Eigen::Matrix<double, 6, 1>& rho) {
    const Matrix6xNd A = L.leftCols<3>();
    const VectorNd b = solveLeastSquares(A, rho);
    double b1, b2;
    if (b[0] < 0) {
      b1 = std::sqrt(-b[0]);
      b2 = b[2] < 0 ? std::sqrt(-b[2]) : 0.0;
    } else {
      b1 = std::sqrt(b[0]);
      b2 = b[2] > 0 ? std::sqrt(b[2]) : 0.0;
    }
    if (b[1] < 0) b1 = -b1;
    return {b1, b2, 0.0, 0.0};
  }

  // N = 3: [b11 b12 b22 b13 b23] (columns 0..4).
  static Eigen::Vector4d approximation3(const Matrix6x10d& L, const Eigen::Matrix<double, 6, 1>& rho) {
    const Matrix6xNd A = L.leftCols<5>();
    const VectorNd b = solveLeastSquares(A, rho);
    double b1, b2;
    if (b[0] < 0) {
      b1 = std::sqrt(-b[0]);
      b2 = b[2] < 0 ? std::sqrt(-b[2]) : 0.0;
    } else {
      b1 = std::sqrt(b[0]);
      b2 = b[2] > 0 ? std::sqrt(b[2]) : 0.0;
    }
    if (b[1] < 0) b1 = -b1;
    const double b3 = b1 != 0 ? b[3] / b1 : 0.0;
    return {b1, b2, b3, 0.0};
  }

  // Minimises sum_p (L_p . monomials(beta) - rho_p)^2 over the four betas.
  static Eigen::Vector4d gaussNewton(const Matrix6x10d& L, const Eigen::Matrix<double, 6, 1>& rho, Eigen::Vector4d b) {
    for (int it = 0; it < kGaussNewtonIterations; ++it) {
      Eigen::Matrix<double, 6, 4> J;
      Eigen::Matrix<double, 6, 1> r;
      for (int p = 0; p < 6; ++p) {
        const auto l = L.row(p);
        J(p, 0) = 2 * l[0] * b[0] + l[1] * b[1] + l[3] * b[2] + l[6] * b[3];
        J(p, 1) = l[1] * b[0] + 2 * l[2] * b[1] + l[4] * b[2] + l[7] * b[3];
        J(p, 2) = l[3] * b[0] + l[4] * b[1] + 2 * l[5] * b[2] + l[8] * b[3];
        J(p, 3) = l[6] * b[0] + l[7] * b[1] + l[8] * b[2] + 2 * l[9] * b[3];
        r[p] = rho[p] - l.dot(monomials(b).transpose());
      }
      // Normal equations: a 4x4 solve is all this tiny, well-posed least-squares problem needs.
      const Eigen::Vector4d step = (J.transpose() * J).ldlt().solve(J.transpose() * r);
      if (!step.allFinite()) break;
      b += step;
    }
    return b;
  }

  std::optional<core::SE3> poseFromBetas(const Eigen::Vector4d& betas) const {
    Eigen::Matrix<double, 12, 1> cc = Eigen::Matrix<double, 12, 1>::Zero();
    for (int k = 0; k < 4; ++k) cc += betas[k] * null_[k];
    std::vector<Eigen::Vector3d> pc(pw_.size());
    double z_sum = 0;
    for (size_t i = 0; i < pw_.size(); ++i) {
      pc[i].setZero();
      for (int j = 0; j < 4; ++j) pc[i] += alphas_[i][j] * cc.segment<3>(3 * j);
      z_sum += pc[i].z();
    }
    // The null-space solution is defined up to sign: the points must be in front of the camera.
    if (z_sum < 0)
      for (auto& p : pc) p = -p;
    const core::SE3 T = alignRigid(pw_, pc);
    if (!T.matrix().allFinite()) return std::nullopt;
    return T;
  }

  const std::vector<Eigen::Vector3d>& pw_;
  const std::vector<Eigen::Vector2d>& xy_;
  std::array<Eigen::Vector3d, 4> cw_;
  std::vector<Eigen::Vector4d> alphas_;
  std::array<Eigen::Matrix<double, 12, 1>, 4> null_;
};

// A pixel-like focal length: OpenCV's solvers have tolerances that assume pixel units.
constexpr double kF = 500.0;
cv::Mat pixelK() { return (cv::Mat_<double>(3, 3) << kF, 0, 0, 0, kF, 0, 0, 0, 1); }

// OpenCV's SQPnP (Terzakis and Lourakis, ECCV 2020) for (nearly) coplanar points, where the four-control-point
// form degenerates. (OpenCV 4.6's IPPE was tried first and returns wrong poses for some off-origin planes.)
std::optional<core::SE3> solvePlanar(const std::vector<Eigen::Vector3d>& pw, const std::vector<Eigen::Vector2d>& xy) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (size_t i = 0; i < pw.size(); ++i) {
    object.emplace_back(pw[i].x(), pw[i].y(), pw[i].z());
    image.emplace_back(kF * xy[i].x(), kF * xy[i].y());
  }
  cv::Mat rvec, tvec;
  try {
    if (!cv::solvePnP(object, image, pixelK(), cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_SQPNP))
      return std::nullopt;
  } catch (const cv::Exception&) {
    return std::nullopt;  // e.g. collinear points
  }
  const Eigen::Vector3d r(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2));
  const Eigen::Vector3d t(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  if (!r.allFinite() || !t.allFinite()) return std::nullopt;
  core::SE3 T = core::SE3::Identity();
  T.linear() = core::expSO3(r);
  T.translation() = t;
  return T;
}

}  // namespace

std::optional<core::SE3> solveEpnp(const std::vector<Eigen::Vector3d>& points_w,
                                   const std::vector<Eigen::Vector2d>& normalized) {
  if (points_w.size() < 4 || points_w.size() != normalized.size()) return std::nullopt;
  Epnp epnp(points_w, normalized);
  const double thickness = epnp.chooseControlPoints();
  std::optional<core::SE3> best;
  double best_error = std::numeric_limits<double>::infinity();
  if (thickness >= kSingularRatio) {
    best = epnp.solve();
    if (best) best_error = reprojectionError(*best, points_w, normalized);
  }
  if (thickness < kTryPlanarRatio) {
    const std::optional<core::SE3> planar = solvePlanar(points_w, normalized);
    if (planar && reprojectionError(*planar, points_w, normalized) < best_error) best = planar;
  }
  return best;
}

}  // namespace amos::geometry
