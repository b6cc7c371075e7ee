#pragma once
// Dense photometric refinement of a tracked frame's pose against its reference keyframe, joint with the feature
// residuals of the pose optimisation (issue 42). The feature pose is limited by the information ~250 inlier
// keypoints carry (docs/experiments/pose-noise-causes.md); thousands of high-gradient pixels of the reference
// keyframe, with their depth, add the constraints that tie the frame to the keyframe it is stored against
// (T_cr), so frames tracked against one keyframe agree with each other.
//
// Cost over the pose T_cw (left perturbation, core/pose.h), for the feature inliers i and template points j:
//   sum_i r_i^T Sigma_i^-1 r_i  +  sum_j huber((I_c(pi(T_cw T_wr p_j)) - (a I_r(j) + b)) / sigma)
// with the reference's affine brightness (a, b) refitted per level (auto exposure), sigma the robust scale
// (1.4826 MAD) of the photometric residuals at the start of each level, coarse to fine over an image pyramid.
// Pixels in either frame's dynamic mask take no part. A step is taken only when it lowers the joint cost, so the
// feature terms hold the pose where the pixels say little; a gate on the distance from the feature pose (a
// 6-dof chi-square bound under the feature information) was tried and not kept
// (docs/experiments/photometric-refinement.md).
//
// Images stay in the camera's raw (distorted) pixel grid: a template point is projected to normalised coordinates,
// through the lens distortion, then K, and the raw pyramid is sampled there (the Jacobian takes the distortion's
// 2x2 Jacobian by the chain rule); template points are back-projected along the undistorted ray of their raw pixel.
// No image is resampled, and a raw pixel inside the image is a real pixel (undistorted images have corners with no
// source). Without distortion this is the plain pinhole path, term for term.
#include <opencv2/core.hpp>
#include <Eigen/Core>

#include <vector>

#include "amos/core/distortion.h"
#include "amos/core/pose.h"
#include "amos/geometry/pose_optimizer.h"

namespace amos::geometry {

struct PhotometricOptions {
  int levels = 2;             // pyramid levels, coarse to fine; level 0 is the full image
  int cell = 8;               // at most one template point per cell x cell pixels of level 0 (cell / 2^l at l)
  double min_gradient = 6;    // grey levels per pixel: weaker gradients carry little information
  double min_depth = 0.3;     // metres: the range where the structured-light depth is measured
  double max_depth = 4.0;
  double depth_edge = 0.03;   // a point whose 3x3 depth neighbourhood spans more than this share of z is dropped
  int mask_margin = 5;        // pixels added around the dynamic mask
  int iterations = 6;         // Gauss-Newton iterations per level (at most; it stops once a step is tiny)
  double huber_k = 1.345;     // Huber threshold in sigmas (95 % efficiency under Gaussian noise)
  int min_points = 200;       // fewer usable template points: no refinement
  void check() const;
};

// A grey image pyramid in the camera's raw (distorted) pixel grid, with the dynamic mask at each level (CV_8U,
// non-zero = excluded). Level 0 is the camera's CV_8U image itself (shared, not copied: a bilinear sample of the
// bytes is the sample of their float conversion), coarser levels CV_32F.
struct PhotometricImage {
  std::vector<cv::Mat> gray, mask;
  std::vector<StereoProjection> intrinsics;  // per level: K scaled about pixel centres, (u + 0.5) / 2^l - 0.5
  core::RadialTangential lens;               // of the raw pixels, on normalised coordinates
  // Squared normalised radius of the image's farthest corner, undistorted: beyond it the lens polynomial can fold
  // rays from outside the view back into the image, so projections there are refused.
  double max_r2 = 0;
  cv::Mat scratch, scratch_float;            // reused by makePhotometricImage
  int levels() const { return static_cast<int>(gray.size()); }
};
// `gray` CV_8U, `mask` CV_8U (or empty: nothing excluded), both in the raw grid of a camera with pinhole part
// `camera` and distortion `lens`.
PhotometricImage makePhotometricImage(const cv::Mat& gray, const cv::Mat& mask, const StereoProjection& camera,
                                      const core::RadialTangential& lens, const PhotometricOptions& options);
// The same into `out`, reusing its buffers: a new frame's images then cost no allocation (on this machine the
// first writes to freshly allocated megabyte images, page faults, cost more than the image operations).
void makePhotometricImage(const cv::Mat& gray, const cv::Mat& mask, const StereoProjection& camera,
                          const core::RadialTangential& lens, const PhotometricOptions& options,
                          PhotometricImage& out);

struct PhotometricPoint {
  Eigen::Vector3d p_r;  // in the reference camera (the undistorted ray of its raw pixel, times the depth)
  double intensity = 0;
};
// The reference keyframe's selected pixels with depth, per level. `depth` (CV_32F, metres) is registered to the raw
// grid of `image` at level 0.
struct PhotometricTemplate {
  std::vector<std::vector<PhotometricPoint>> levels;
  bool empty() const { return levels.empty(); }
};
PhotometricTemplate makePhotometricTemplate(const PhotometricImage& image, const cv::Mat& depth,
                                            const PhotometricOptions& options);

struct PhotometricProblem {
  const std::vector<PoseObservation>* features = nullptr;  // the pose optimiser's inliers
  StereoProjection projection;                             // of the feature observations (level 0)
  const PhotometricTemplate* reference = nullptr;
  core::SE3 T_rw = core::SE3::Identity();                  // the reference keyframe's pose
  const PhotometricImage* current = nullptr;
};

struct PhotometricResult {
  core::SE3 T_cw = core::SE3::Identity();
  bool accepted = false;
  int points = 0;          // template points used at level 0
  double sigma = 0;        // photometric scale at level 0 (grey levels)
  // The photometric residuals' Gauss-Newton information at the result (level 0, Huber weights, the robust scale),
  // about the left perturbation of T_cw (and of T_cr): what the pixels alone say about the pose relative to the
  // reference, apart from the keypoints.
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
};

PhotometricResult refinePosePhotometrically(const PhotometricProblem& problem, const core::SE3& initial_T_cw,
                                            const PhotometricOptions& options);

}  // namespace amos::geometry
