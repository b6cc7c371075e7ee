#include "amos/dynamic/epipolar_check.h"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::dynamic {

void EpipolarOptions::check() const {
  core::requirePositive(ransac_threshold_px, "ransac_threshold_px");
  core::requireOption(
      std::isfinite(dynamic_threshold_px) && dynamic_threshold_px >= ransac_threshold_px,
      core::option(dynamic_threshold_px, "dynamic_threshold_px"),
      fmt::format("must be >= ransac_threshold_px = {}, got {}", ransac_threshold_px, dynamic_threshold_px),
      {core::option(ransac_threshold_px, "ransac_threshold_px")});
  core::requireOption(confidence > 0 && confidence < 1, core::option(confidence, "confidence"),
                      fmt::format("must lie in (0, 1), got {}", confidence));
  core::requireAtLeast(max_iterations, "max_iterations", 1);
  core::requireAtLeast(min_fit_points, "min_fit_points", 15);
  core::requireAtLeast(min_dynamic_points, "min_dynamic_points", 1);
}

double epipolarDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& p_last, const Eigen::Vector2d& p_current) {
  const Eigen::Vector3d line = F * p_last.homogeneous();  // [A, B, C]
  const double norm = std::hypot(line.x(), line.y());
  if (norm <= 0) return std::numeric_limits<double>::infinity();
  return std::abs(p_current.homogeneous().dot(line)) / norm;
}

Eigen::Matrix3d fundamentalFromPose(const Eigen::Matrix3d& K, const core::SE3& T_cl) {
  const Eigen::Matrix3d K_inv = K.inverse();
  return K_inv.transpose() * core::skew(T_cl.translation()) * T_cl.rotation() * K_inv;
}

namespace {

constexpr int kMinCorrespondences = 15;

int countWithin(const Eigen::Matrix3d& F, const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b,
                double threshold, std::vector<uchar>* mask) {
  int count = 0;
  if (mask) mask->assign(a.size(), 0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (epipolarDistance(F, {a[i].x, a[i].y}, {b[i].x, b[i].y}) <= threshold) {
      ++count;
      if (mask) (*mask)[i] = 1;
    }
  }
  return count;
}

}  // namespace

FundamentalFit fitFundamental(const std::vector<cv::Point2f>& last, const std::vector<cv::Point2f>& current,
                              const EpipolarOptions& options) {
  options.check();
  core::require(last.size() == current.size(), "fitFundamental: point lists differ in length");
  FundamentalFit fit;
  if (static_cast<int>(last.size()) < kMinCorrespondences) return fit;

  // First fit: USAC's LO-RANSAC with uniform sampling, MSAC score and a fixed RNG state (deterministic).
  cv::UsacParams usac;
  usac.confidence = options.confidence;
  usac.isParallel = false;
  usac.maxIterations = options.max_iterations;
  usac.randomGeneratorState = options.seed;
  usac.sampler = cv::SAMPLING_UNIFORM;
  usac.score = cv::SCORE_METHOD_MSAC;
  usac.loMethod = cv::LOCAL_OPTIM_INNER_LO;
  usac.threshold = options.ransac_threshold_px;
  cv::Mat mask;
  cv::Mat F1;
  try {
    F1 = cv::findFundamentalMat(last, current, mask, usac);
  } catch (const cv::Exception&) {
    return fit;  // degenerate configuration: no F
  }
  if (F1.empty() || F1.rows != 3 || F1.cols != 3) return fit;
  Eigen::Matrix3d F;
  cv::cv2eigen(F1, F);
  fit.ransac_inliers = countWithin(F, last, current, options.ransac_threshold_px, nullptr);

  // Second fit (paper III-C): drop the points beyond the dynamic threshold of the first F, refit by the
  // normalised 8-point least squares on the rest.
  std::vector<uchar> keep;
  fit.refit_points = countWithin(F, last, current, options.dynamic_threshold_px, &keep);
  if (fit.refit_points >= kMinCorrespondences) {
    std::vector<cv::Point2f> a, b;
    for (std::size_t i = 0; i < last.size(); ++i)
      if (keep[i]) a.push_back(last[i]), b.push_back(current[i]);
    cv::Mat F2 = cv::findFundamentalMat(a, b, cv::FM_8POINT);
    if (!F2.empty() && F2.rows == 3 && F2.cols == 3) {
      Eigen::Matrix3d F2e;
      cv::cv2eigen(F2, F2e);
      // Keep the refit only when it explains at least as many points as RANSAC's model.
      const int refit_inliers = countWithin(F2e, last, current, options.ransac_threshold_px, nullptr);
      if (refit_inliers >= fit.ransac_inliers) F = F2e;
    }
  }
  fit.F = F;
  fit.final_inliers = countWithin(F, last, current, options.ransac_threshold_px, nullptr);
  fit.ok = fit.final_inliers >= kMinCorrespondences;
  return fit;
}

}  // namespace amos::dynamic
