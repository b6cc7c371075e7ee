#include "amos/evidence/rigid_movers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/dynamic/frame_regions.h"
#include "amos/dynamic/robust_scale.h"

namespace amos::evidence {

using namespace dynamic;  // NOLINT(google-build-using-namespace): the front end's types

bool withinReach(const cv::Rect2f& r, const cv::Point2f& p, float reach) {
  return p.x >= r.x - reach && p.y >= r.y - reach && p.x <= r.x + r.width + reach && p.y <= r.y + r.height + reach;
}

namespace {

bool nearAnyMover(const std::vector<RigidMover>& movers, const cv::Point2f& p, float reach) {
  return std::any_of(movers.begin(), movers.end(), [&](const RigidMover& m) { return withinReach(m.region, p, reach); });
}

// Current-camera points (lifted with the current depth, backProjectTracks' trust rules) of raw pixels.
std::vector<std::optional<Eigen::Vector3d>> liftPixels(const std::vector<cv::Point2f>& pixels, const cv::Mat& depth,
                                                       const core::PinholeCamera& camera,
                                                       const ReprojectionOptions& reprojection) {
  std::vector<PointTrack> at(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) at[i].last = pixels[i];
  return backProjectTracks(at, depth, core::SE3::Identity(), camera, reprojection);
}

core::SE3 poseOf(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d r;
  Eigen::Vector3d t;
  cv::cv2eigen(R, r);
  cv::cv2eigen(tvec, t);
  core::SE3 T = core::SE3::Identity();
  T.linear() = r;
  T.translation() = t;
  return T;
}

void toRvecTvec(const core::SE3& T, cv::Mat& rvec, cv::Mat& tvec) {
  cv::Mat R;
  cv::eigen2cv(Eigen::Matrix3d(T.linear()), R);
  cv::Rodrigues(R, rvec);
  cv::eigen2cv(Eigen::Vector3d(T.translation()), tvec);
}

double reprojectionError(const core::SE3& T, const Eigen::Vector3d& X, const cv::Point2f& seen,
                         const core::PinholeCamera& camera) {
  const Eigen::Vector3d p = T * X;
  if (p.z() <= 1e-6) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d uv = camera.project(p);
  return std::hypot(uv.x() - seen.x, uv.y() - seen.y);
}

// Refines T (current -> baseline camera) on the correspondences by Levenberg-Marquardt (undistorted pixels).
core::SE3 refine(const core::SE3& T, const std::vector<cv::Point3f>& object, const std::vector<cv::Point2f>& image,
                 const cv::Mat& K) {
  if (object.size() < 6) return T;
  cv::Mat rvec, tvec;
  toRvecTvec(T, rvec, tvec);
  cv::solvePnPRefineLM(object, image, K, cv::noArray(), rvec, tvec);
  return poseOf(rvec, tvec);
}

// Bilinear intensity of a CV_8UC1 image at (x, y), inside [0, cols - 1) x [0, rows - 1).
float bilinear(const cv::Mat& img, float x, float y) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float ax = x - x0, ay = y - y0;
  const uchar* r0 = img.ptr<uchar>(y0);
  const uchar* r1 = img.ptr<uchar>(y0 + 1);
  return (1 - ay) * ((1 - ax) * r0[x0] + ax * r0[x0 + 1]) + ay * ((1 - ax) * r1[x0] + ax * r1[x0 + 1]);
}

// Mean absolute difference of the 3x3 patch of `gray` at integer (u, v) and that of `baseline` at raw (x, y);
// infinity where the baseline patch leaves the image or the baseline frame did not see the point (its depth at
// (x, y) nearer than z by more than max(2 cm, 4 %)).
double patchDifference(const cv::Mat& gray, int u, int v, const cv::Mat& baseline, const cv::Mat& baseline_depth,
                       cv::Point2f at, double z) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!(at.x >= 1.f && at.y >= 1.f && at.x < baseline.cols - 2.f && at.y < baseline.rows - 2.f)) return kInf;
  if (!baseline_depth.empty()) {
    const float measured = baseline_depth.at<float>(cvRound(at.y), cvRound(at.x));
    if (!(measured > 0) || measured < z - std::max(0.02, 0.04 * z)) return kInf;
  }
  double sum = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    const uchar* row = gray.ptr<uchar>(v + dy);
    for (int dx = -1; dx <= 1; ++dx) sum += std::fabs(row[u + dx] - bilinear(baseline, at.x + dx, at.y + dy));
  }
  return sum / 9.0;
}

// The long-baseline points with a trusted depth, lifted into the current camera and split by whether they moved.
struct LiftedPoints {
  std::vector<cv::Point3f> object;  // current-camera point
  std::vector<cv::Point2f> image;   // undistorted pixel where LK found it in the baseline frame
  std::vector<cv::Point2f> pixel;   // raw pixel in the current frame
};
struct SplitPoints {
  LiftedPoints still, moving;
};

SplitPoints liftBaselinePoints(const BaselineMotion& motion, const cv::Mat& depth, const core::PinholeCamera& camera,
                               const ReprojectionOptions& reprojection) {
  std::vector<cv::Point2f> current, found;
  for (const BaselinePoint& p : motion.points) current.push_back(p.current), found.push_back(p.found);
  const std::vector<std::optional<Eigen::Vector3d>> lifted = liftPixels(current, depth, camera, reprojection);
  const std::vector<cv::Point2f> seen = camera.undistort(found);
  SplitPoints split;
  for (std::size_t i = 0; i < motion.points.size(); ++i) {
    if (!lifted[i]) continue;
    const cv::Point3f X(static_cast<float>(lifted[i]->x()), static_cast<float>(lifted[i]->y()),
                        static_cast<float>(lifted[i]->z()));
    LiftedPoints& to = motion.points[i].moving ? split.moving : split.still;
    to.object.push_back(X), to.image.push_back(seen[i]), to.pixel.push_back(current[i]);
  }
  return split;
}

// One rigid motion among the moving points not yet `used` (which it marks): its refined motion and inliers, or none
// when too few points are left or agree. Its shift and region are those of a RigidMover.
std::optional<RigidMover> fitNextMotion(const LiftedPoints& moving, const core::SE3& T_bc_static,
                                        const core::PinholeCamera& camera, const RigidMoverOptions& options,
                                        std::vector<bool>& used, std::vector<int>& inlier_points) {
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  std::vector<int> index;
  for (std::size_t i = 0; i < moving.object.size(); ++i)
    if (!used[i]) object.push_back(moving.object[i]), image.push_back(moving.image[i]), index.push_back(int(i));
  if (static_cast<int>(object.size()) < options.min_inliers) return std::nullopt;
  const cv::Mat K = camera.K();
  cv::Mat rvec, tvec;
  std::vector<int> ransac_inliers;
  // OpenCV's RANSAC draws from a fixed seed: deterministic.
  if (!cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, 200,
                          static_cast<float>(options.inlier_px), 0.99, ransac_inliers, cv::SOLVEPNP_EPNP))
    return std::nullopt;
  if (static_cast<int>(ransac_inliers.size()) < options.min_inliers) return std::nullopt;
  core::SE3 T = poseOf(rvec, tvec);
  std::vector<cv::Point3f> in_object;
  std::vector<cv::Point2f> in_image;
  for (int k : ransac_inliers) in_object.push_back(object[k]), in_image.push_back(image[k]);
  T = refine(T, in_object, in_image, K);
  // Its inliers under the refined motion, and how far it moves them from the static world's prediction.
  std::vector<int> inliers;
  std::vector<double> shifts;
  for (std::size_t k = 0; k < object.size(); ++k) {
    const Eigen::Vector3d X(object[k].x, object[k].y, object[k].z);
    if (reprojectionError(T, X, image[k], camera) > options.inlier_px) continue;
    inliers.push_back(static_cast<int>(k));
    const Eigen::Vector3d ps = T_bc_static * X, pm = T * X;
    if (ps.z() > 1e-6 && pm.z() > 1e-6) shifts.push_back((camera.project(ps) - camera.project(pm)).norm());
  }
  if (static_cast<int>(inliers.size()) < options.min_inliers || shifts.empty()) return std::nullopt;
  inlier_points.clear();
  for (int k : inliers) used[index[k]] = true, inlier_points.push_back(index[k]);
  RigidMover mover;
  mover.T_bc = T;
  mover.inliers = static_cast<int>(inliers.size());
  mover.shift_px = upperMedian(shifts);
  return mover;
}

// The box around the points in the current frame.
cv::Rect2f boxAround(const std::vector<cv::Point2f>& pixel, const std::vector<int>& points) {
  float x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (int k : points) {
    const cv::Point2f& p = pixel[k];
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  return cv::Rect2f(x0, y0, x1 - x0, y1 - y0);
}

// Rigid motions among the moving points, one after the other on what the previous ones left.
std::vector<RigidMover> findMovers(const SplitPoints& points, const core::SE3& T_bc_static,
                                   const core::PinholeCamera& camera, const RigidMoverOptions& options) {
  std::vector<RigidMover> movers;
  std::vector<bool> used(points.moving.object.size(), false);
  std::vector<int> inliers;
  for (int m = 0; m < options.max_movers; ++m) {
    std::optional<RigidMover> mover = fitNextMotion(points.moving, T_bc_static, camera, options, used, inliers);
    if (!mover) break;
    if (mover->shift_px <= options.inlier_px) continue;  // a motion the static world explains as well: not a mover
    // Where it is: the box around its inliers in the current frame. A rigid body's points lie together; a motion
    // that a few points scattered over the static world happen to share (LK slips, a real sensor's structured
    // depth errors) spans points that stayed: more of those than of its own, and it is no mover.
    const cv::Rect2f region = boxAround(points.moving.pixel, inliers);
    const std::vector<cv::Point2f>& still = points.still.pixel;
    const auto stayed_inside = std::count_if(still.begin(), still.end(), [&](const cv::Point2f& p) {
      return p.x >= region.x && p.y >= region.y && p.x <= region.x + region.width && p.y <= region.y + region.height;
    });
    if (stayed_inside >= static_cast<long>(mover->inliers)) continue;
    mover->region = region;
    movers.push_back(*mover);
  }
  return movers;
}

// The grid samples near a mover with a trusted depth, and where each hypothesis (0: the static world, h: mover h-1)
// puts them in the baseline frame.
struct SamplePredictions {
  std::vector<cv::Point2f> pixel;                     // raw, current frame
  std::vector<std::vector<cv::Point2f>> undistorted;  // per hypothesis, per sample
  std::vector<std::vector<cv::Point2f>> raw;
  std::vector<std::vector<double>> z;                 // depth in the baseline camera, -1 behind it
};

SamplePredictions predictSamples(const RigidMoverVerdict& out, const RigidMoverFrames& frames,
                                 const ReprojectionOptions& reprojection, const RigidMoverOptions& options) {
  const cv::Mat& gray = frames.current.gray;
  const core::PinholeCamera& camera = frames.camera;
  const int step = options.sample_step_px;
  std::vector<cv::Point2f> samples;
  // A mover speaks for the samples around its points, up to Dynamic.Boundary.radius beyond them (the paper's reach
  // of a border point into the cluster beside it): a door's plain panel or a box's edge lies between or just
  // beyond its corners, the rest of the image does not.
  const float reach = static_cast<float>(options.region_reach_px);
  const int first = std::max(4, step / 2);  // windowStructure's margin
  for (int v = first; v < gray.rows - 4; v += step)
    for (int u = first; u < gray.cols - 4; u += step) {
      const cv::Point2f p(static_cast<float>(u), static_cast<float>(v));
      if (nearAnyMover(out.movers, p, reach)) samples.push_back(p);
    }
  const std::vector<std::optional<Eigen::Vector3d>> points =
      liftPixels(samples, frames.current.depth, camera, reprojection);
  SamplePredictions s;
  std::vector<Eigen::Vector3d> X;
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (points[i]) s.pixel.push_back(samples[i]), X.push_back(*points[i]);
  const std::size_t hypotheses = 1 + out.movers.size();
  s.undistorted.assign(hypotheses, std::vector<cv::Point2f>(X.size()));
  s.z.assign(hypotheses, std::vector<double>(X.size(), -1));
  for (std::size_t h = 0; h < hypotheses; ++h) {
    const core::SE3& T = h == 0 ? out.T_bc_static : out.movers[h - 1].T_bc;
    for (std::size_t i = 0; i < X.size(); ++i) {
      const Eigen::Vector3d p = T * X[i];
      if (p.z() <= 1e-6) continue;
      const Eigen::Vector2d uv = camera.project(p);
      s.undistorted[h][i] = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
      s.z[h][i] = p.z();
    }
  }
  s.raw.resize(hypotheses);
  for (std::size_t h = 0; h < hypotheses; ++h) s.raw[h] = camera.distort(s.undistorted[h]);
  return s;
}

// Each sample's vote: for the mover whose prediction matches its patch better than the static world's by the margin
// (or against it), with each mover's tally of both.
struct SampleVotes {
  std::vector<RigidSampleVote> votes;
  std::vector<int> mover_tally, static_tally;  // per mover
};

SampleVotes voteSamples(const RigidMoverVerdict& out, const SamplePredictions& s, const RigidMoverFrames& frames,
                        const SuperpixelLabels& superpixels, const RigidMoverOptions& options) {
  const cv::Mat& gray = frames.current.gray;
  const cv::Mat& baseline_gray = frames.baseline.gray;
  const cv::Mat& baseline_depth = frames.baseline.depth;
  const float reach = static_cast<float>(options.region_reach_px);
  const std::size_t hypotheses = 1 + out.movers.size();
  const double min_texture = options.min_gradient * options.min_gradient;
  SampleVotes result;
  result.mover_tally.assign(out.movers.size(), 0);
  result.static_tally.assign(out.movers.size(), 0);
  for (std::size_t i = 0; i < s.pixel.size(); ++i) {
    const cv::Point2f& pixel = s.pixel[i];
    if (s.z[0][i] <= 0) continue;
    const int u = static_cast<int>(pixel.x), v = static_cast<int>(pixel.y);
    const double e_static = patchDifference(gray, u, v, baseline_gray, baseline_depth, s.raw[0][i], s.z[0][i]);
    if (!std::isfinite(e_static)) continue;
    double e_mover = std::numeric_limits<double>::infinity();
    int best = -1;
    const WindowStructure structure = windowStructure(gray, u, v);
    for (std::size_t h = 1; h < hypotheses; ++h) {
      if (s.z[h][i] <= 0 || !withinReach(out.movers[h - 1].region, pixel, reach)) continue;
      const cv::Point2f d = s.undistorted[h][i] - s.undistorted[0][i];
      const double separation = std::hypot(d.x, d.y);
      if (separation < options.min_separation_px) continue;
      // Only a patch textured along the separation can tell the two positions apart: on a striped surface (wood
      // grain, a row of book spines) a hypothesis that moves a sample along the stripes matches as well as the
      // right one, and a fraction of a pixel across them decides at random.
      if (structure.along(d.x / separation, d.y / separation) < min_texture) continue;
      const double e = patchDifference(gray, u, v, baseline_gray, baseline_depth, s.raw[h][i], s.z[h][i]);
      if (e < e_mover) e_mover = e, best = static_cast<int>(h) - 1;
    }
    if (best < 0) continue;
    const int sp = labelAt(superpixels.labels, pixel);
    if (sp < 0 || sp >= superpixels.count) continue;
    if (e_mover + options.intensity_margin < e_static)
      result.votes.push_back({sp, best}), ++result.mover_tally[best];
    else if (e_static + options.intensity_margin < e_mover)
      result.votes.push_back({sp, -1 - best}), ++result.static_tally[best];
  }
  return result;
}

// The superpixels the kept movers' votes decide, and the movers kept. A mover must explain the samples around its
// own points better than the static world does; a motion fitted to a real sensor's structured errors (TUM fr2/desk:
// the near desk at the image bottom, where depth and colour were taken ~20 ms apart) does not, and its votes are
// dropped.
void countVotes(const SampleVotes& sample_votes, const RigidMoverOptions& options, RigidMoverVerdict& out) {
  std::vector<int> mover_votes(out.moving.size(), 0), static_votes(out.moving.size(), 0);
  std::vector<bool> kept_mover(out.movers.size());
  for (std::size_t m = 0; m < out.movers.size(); ++m)
    kept_mover[m] = sample_votes.mover_tally[m] > sample_votes.static_tally[m];
  for (const RigidSampleVote& vote : sample_votes.votes) {
    if (vote.mover >= 0 && kept_mover[vote.mover])
      ++mover_votes[vote.superpixel], ++out.mover_votes;
    else if (vote.mover < 0)
      ++static_votes[vote.superpixel], ++out.static_votes;
  }
  for (std::size_t s = 0; s < out.moving.size(); ++s) {
    out.moving[s] = mover_votes[s] >= options.min_samples && mover_votes[s] > 2 * static_votes[s];
    out.moving_superpixels += out.moving[s];
  }
  std::vector<RigidMover> confirmed;
  for (std::size_t m = 0; m < out.movers.size(); ++m)
    if (kept_mover[m]) confirmed.push_back(out.movers[m]);
  out.movers = std::move(confirmed);
}

void checkFrames(const RigidMoverFrames& frames, const cv::Mat& labels) {
  const cv::Mat& gray = frames.current.gray;
  const cv::Mat& depth = frames.current.depth;
  const cv::Mat& baseline_gray = frames.baseline.gray;
  const cv::Mat& baseline_depth = frames.baseline.depth;
  core::require(gray.type() == CV_8UC1 && baseline_gray.type() == CV_8UC1 && gray.size() == baseline_gray.size() &&
                    depth.type() == CV_32F && depth.size() == gray.size() && labels.type() == CV_32S &&
                    labels.size() == gray.size(),
                "rigidMoverSuperpixels: gray and baseline gray CV_8UC1, depth CV_32F, labels CV_32S, one size");
  core::require(baseline_depth.empty() || (baseline_depth.type() == CV_32F && baseline_depth.size() == gray.size()),
                "rigidMoverSuperpixels: baseline depth must be empty or CV_32F of the image size");
}

}  // namespace

RigidMoverVerdict rigidMoverSuperpixels(const BaselineMotion& motion, const RigidMoverFrames& frames,
                                        const SuperpixelLabels& superpixels, const ReprojectionOptions& reprojection,
                                        const RigidMoverOptions& options) {
  checkFrames(frames, superpixels.labels);
  RigidMoverVerdict out;
  out.moving.assign(std::max(0, superpixels.count), false);
  out.T_bc_static = frames.baseline.T_cw * frames.current.T_cw.inverse();
  if (!motion.ok || motion.moving_points < options.min_inliers) return out;
  const SplitPoints points = liftBaselinePoints(motion, frames.current.depth, frames.camera, reprojection);
  // The static world's motion, refined on the points that stayed (the two tracked poses' error, which the long
  // baseline removes as a common shift, is here part of the motion).
  out.T_bc_static = refine(out.T_bc_static, points.still.object, points.still.image, frames.camera.K());
  out.movers = findMovers(points, out.T_bc_static, frames.camera, options);
  if (out.movers.empty()) return out;
  // Every sample of the grid near a mover, with a trusted depth, votes for the hypothesis that explains its patch.
  const SamplePredictions samples = predictSamples(out, frames, reprojection, options);
  countVotes(voteSamples(out, samples, frames, superpixels, options), options, out);
  return out;
}

std::vector<bool> superpixelsNearBoxes(const std::vector<Superpixel>& superpixels,
                                       const std::vector<cv::Rect2f>& boxes, int reach_px) {
  const float reach = static_cast<float>(reach_px);
  std::vector<bool> near(superpixels.size());
  for (std::size_t s = 0; s < superpixels.size(); ++s) {
    const cv::Point2f centroid(superpixels[s].x, superpixels[s].y);
    near[s] = std::any_of(boxes.begin(), boxes.end(),
                          [&](const cv::Rect2f& box) { return withinReach(box, centroid, reach); });
  }
  return near;
}

std::vector<bool> superpixelsNearMovers(const std::vector<Superpixel>& superpixels,
                                        const std::vector<RigidMover>& movers, int reach_px) {
  std::vector<cv::Rect2f> regions;
  regions.reserve(movers.size());
  for (const RigidMover& m : movers) regions.push_back(m.region);
  return superpixelsNearBoxes(superpixels, regions, reach_px);
}

}  // namespace amos::evidence
