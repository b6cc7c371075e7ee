#pragma once
// Bundle adjustment of keyframe poses and point positions with Ceres, as a pure function of plain data so it can
// be tested on synthetic scenes and run without holding the map lock. Residuals are ORB-SLAM2's: (u, v) for a
// keypoint without depth, (u, v, u_r) with the virtual right coordinate for one with depth, weighted by the
// keypoint's pyramid level; Huber loss at the 95% chi-square thresholds. Two stages as in ORB-SLAM2's local BA:
// a robust solve, then outliers are dropped and the rest refined without the robust loss.
#include <Eigen/Core>
#include <atomic>
#include <vector>

#include "amos/core/pose.h"
#include "amos/geometry/pose_optimizer.h"

namespace amos::mapping {

struct BundleAdjustmentOptions {
  int iterations_robust = 5;   // LocalBA.iterationsRobust: first stage (Huber)
  int iterations_refine = 10;  // LocalBA.iterationsRefine: second stage, outliers removed, no robust loss
  double chi2_mono = 5.991;
  double chi2_stereo = 7.815;
  int num_threads = 1;         // LocalBA.threads (1 keeps runs bit-identical)
  // LocalBA.maxKeyFrames: the local window is the new keyframe and at most this many of its most covisible
  // neighbours (0 = all of them, ORB-SLAM2's window); the others that see its points stay fixed. In a room every
  // keyframe soon sees every other, and the window, and the cost of each solve, then grows with the map. 20 is
  // below that only in rooms mapped for a while: Bonn crowd full (45 keyframes): mapping CPU 31.6 -> 23.1 ms per
  // frame, ATE 1.80 -> 1.58 cm (deterministic); fr2 desk and the 600-frame static_loop (<= 28 keyframes): unchanged.
  int max_keyframes = 20;
  void check() const;
};

struct BaKeyFrame {
  core::SE3 T_cw = core::SE3::Identity();
  bool fixed = false;
};

struct BaPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

struct BaObservation {
  int keyframe = 0;  // index into BaProblem::keyframes
  int point = 0;     // index into BaProblem::points
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  double u_right = -1;  // < 0: no depth
  double inv_sigma2 = 1;
};

// A measured relative pose between two keyframes, independent of the keypoint observations: the dense photometric
// alignment of keyframe `a` against keyframe `b` when `a` was tracked (map::PoseLink). Residual
// sqrt(information) * log(T_aw T_bw^-1 T_ab^-1), Huber at the 6-dof 95 % chi-square bound in the robust stage.
struct BaRelativePose {
  int a = 0, b = 0;  // indices into BaProblem::keyframes
  core::SE3 T_ab = core::SE3::Identity();
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Identity();
};

struct BaProblem {
  geometry::StereoProjection projection;
  std::vector<BaKeyFrame> keyframes;
  std::vector<BaPoint> points;
  std::vector<BaObservation> observations;
  std::vector<BaRelativePose> relative_poses;
};

struct BaResult {
  std::vector<core::SE3> T_cw;             // per keyframe
  std::vector<Eigen::Vector3d> positions;  // per point
  std::vector<bool> outlier;               // per observation: fails the chi-square test (or is behind) at the end
  bool aborted = false;                    // stopped early by the abort flag: results are still consistent
  int iterations = 0;
  double initial_cost = 0, final_cost = 0;
};

// abort: when non-null and set, the solver stops at the next iteration (tracking wants a new keyframe in).
BaResult solveBundleAdjustment(const BaProblem& problem, const BundleAdjustmentOptions& options,
                               const std::atomic<bool>* abort = nullptr);

}  // namespace amos::mapping
