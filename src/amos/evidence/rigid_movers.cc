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

}  // namespace

RigidMoverVerdict rigidMoverSuperpixels(const BaselineMotion& motion, const cv::Mat& gray, const cv::Mat& depth,
                                        const core::SE3& T_cw, const cv::Mat& baseline_gray,
                                        const cv::Mat& baseline_depth, const core::SE3& T_cw_baseline,
                                        const core::PinholeCamera& camera, const cv::Mat& labels, int count,
                                        const ReprojectionOptions& reprojection, const RigidMoverOptions& options) {
  core::require(gray.type() == CV_8UC1 && baseline_gray.type() == CV_8UC1 && gray.size() == baseline_gray.size() &&
                    depth.type() == CV_32F && depth.size() == gray.size() && labels.type() == CV_32S &&
                    labels.size() == gray.size(),
                "rigidMoverSuperpixels: gray and baseline gray CV_8UC1, depth CV_32F, labels CV_32S, one size");
  core::require(baseline_depth.empty() || (baseline_depth.type() == CV_32F && baseline_depth.size() == gray.size()),
                "rigidMoverSuperpixels: baseline depth must be empty or CV_32F of the image size");
  RigidMoverVerdict out;
  out.moving.assign(std::max(0, count), false);
  out.T_bc_static = T_cw_baseline * T_cw.inverse();
  if (!motion.ok || motion.moving_points < options.min_inliers) return out;

  // The correspondences: current-camera point -> undistorted pixel where LK found it in the baseline frame.
  std::vector<cv::Point2f> current, found;
  for (const BaselinePoint& p : motion.points) current.push_back(p.current), found.push_back(p.found);
  const std::vector<std::optional<Eigen::Vector3d>> lifted = liftPixels(current, depth, camera, reprojection);
  const std::vector<cv::Point2f> seen = camera.undistort(found);
  std::vector<cv::Point3f> still_object, moving_object;
  std::vector<cv::Point2f> still_image, moving_image, still_pixel, moving_pixel;  // pixel: raw, current frame
  for (std::size_t i = 0; i < motion.points.size(); ++i) {
    if (!lifted[i]) continue;
    const cv::Point3f X(static_cast<float>(lifted[i]->x()), static_cast<float>(lifted[i]->y()),
                        static_cast<float>(lifted[i]->z()));
    if (motion.points[i].moving)
      moving_object.push_back(X), moving_image.push_back(seen[i]), moving_pixel.push_back(current[i]);
    else
      still_object.push_back(X), still_image.push_back(seen[i]), still_pixel.push_back(current[i]);
  }
  const cv::Mat K = camera.K();
  // The static world's motion, refined on the points that stayed (the two tracked poses' error, which the long
  // baseline removes as a common shift, is here part of the motion).
  out.T_bc_static = refine(out.T_bc_static, still_object, still_image, K);

  // Rigid motions among the moving points, one after the other on what the previous ones left.
  std::vector<bool> used(moving_object.size(), false);
  for (int m = 0; m < options.max_movers; ++m) {
    std::vector<cv::Point3f> object;
    std::vector<cv::Point2f> image;
    std::vector<int> index;
    for (std::size_t i = 0; i < moving_object.size(); ++i)
      if (!used[i]) object.push_back(moving_object[i]), image.push_back(moving_image[i]), index.push_back(int(i));
    if (static_cast<int>(object.size()) < options.min_inliers) break;
    cv::Mat rvec, tvec;
    std::vector<int> ransac_inliers;
    // OpenCV's RANSAC draws from a fixed seed: deterministic.
    if (!cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, 200,
                            static_cast<float>(options.inlier_px), 0.99, ransac_inliers, cv::SOLVEPNP_EPNP))
      break;
    if (static_cast<int>(ransac_inliers.size()) < options.min_inliers) break;
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
      const Eigen::Vector3d ps = out.T_bc_static * X, pm = T * X;
      if (ps.z() > 1e-6 && pm.z() > 1e-6) shifts.push_back((camera.project(ps) - camera.project(pm)).norm());
    }
    if (static_cast<int>(inliers.size()) < options.min_inliers || shifts.empty()) break;
    for (int k : inliers) used[index[k]] = true;
    const double shift = upperMedian(shifts);
    if (shift <= options.inlier_px) continue;  // a motion the static world explains as well: not a mover
    // Where it is: the box around its inliers in the current frame. A rigid body's points lie together; a motion
    // that a few points scattered over the static world happen to share (LK slips, a real sensor's structured
    // depth errors) spans points that stayed: more of those than of its own, and it is no mover.
    float x0 = std::numeric_limits<float>::max(), y0 = x0, x1 = -x0, y1 = -x0;
    for (int k : inliers) {
      const cv::Point2f& p = moving_pixel[index[k]];
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
    const cv::Rect2f region(x0, y0, x1 - x0, y1 - y0);
    const auto stayed_inside = std::count_if(still_pixel.begin(), still_pixel.end(), [&](const cv::Point2f& p) {
      return p.x >= region.x && p.y >= region.y && p.x <= region.x + region.width && p.y <= region.y + region.height;
    });
    if (stayed_inside >= static_cast<long>(inliers.size())) continue;
    out.movers.push_back({T, static_cast<int>(inliers.size()), shift, region});
  }
  if (out.movers.empty()) return out;

  // Every sample of the grid near a mover, with a trusted depth, votes for the hypothesis that explains its patch.
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
  const std::vector<std::optional<Eigen::Vector3d>> points = liftPixels(samples, depth, camera, reprojection);
  std::vector<int> kept;
  std::vector<Eigen::Vector3d> X;
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (points[i]) kept.push_back(static_cast<int>(i)), X.push_back(*points[i]);
  const std::size_t hypotheses = 1 + out.movers.size();
  // Predictions (undistorted, for the separation; raw, for the image) and depths per hypothesis.
  std::vector<std::vector<cv::Point2f>> undistorted(hypotheses, std::vector<cv::Point2f>(X.size()));
  std::vector<std::vector<double>> z(hypotheses, std::vector<double>(X.size(), -1));
  for (std::size_t h = 0; h < hypotheses; ++h) {
    const core::SE3& T = h == 0 ? out.T_bc_static : out.movers[h - 1].T_bc;
    for (std::size_t i = 0; i < X.size(); ++i) {
      const Eigen::Vector3d p = T * X[i];
      if (p.z() <= 1e-6) continue;
      const Eigen::Vector2d uv = camera.project(p);
      undistorted[h][i] = cv::Point2f(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
      z[h][i] = p.z();
    }
  }
  std::vector<std::vector<cv::Point2f>> raw(hypotheses);
  for (std::size_t h = 0; h < hypotheses; ++h) raw[h] = camera.distort(undistorted[h]);
  std::vector<int> mover_votes(out.moving.size(), 0), static_votes(out.moving.size(), 0);
  std::vector<RigidSampleVote> votes;
  const double min_texture = options.min_gradient * options.min_gradient;
  std::vector<int> mover_tally(out.movers.size(), 0), static_tally(out.movers.size(), 0);
  for (std::size_t i = 0; i < X.size(); ++i) {
    const cv::Point2f& pixel = samples[kept[i]];
    if (z[0][i] <= 0) continue;
    const int u = static_cast<int>(pixel.x), v = static_cast<int>(pixel.y);
    const double e_static = patchDifference(gray, u, v, baseline_gray, baseline_depth, raw[0][i], z[0][i]);
    if (!std::isfinite(e_static)) continue;
    double e_mover = std::numeric_limits<double>::infinity();
    int best = -1;
    const WindowStructure structure = windowStructure(gray, u, v);
    for (std::size_t h = 1; h < hypotheses; ++h) {
      if (z[h][i] <= 0 || !withinReach(out.movers[h - 1].region, pixel, reach)) continue;
      const cv::Point2f d = undistorted[h][i] - undistorted[0][i];
      const double separation = std::hypot(d.x, d.y);
      if (separation < options.min_separation_px) continue;
      // Only a patch textured along the separation can tell the two positions apart: on a striped surface (wood
      // grain, a row of book spines) a hypothesis that moves a sample along the stripes matches as well as the
      // right one, and a fraction of a pixel across them decides at random.
      if (structure.along(d.x / separation, d.y / separation) < min_texture) continue;
      const double e = patchDifference(gray, u, v, baseline_gray, baseline_depth, raw[h][i], z[h][i]);
      if (e < e_mover) e_mover = e, best = static_cast<int>(h) - 1;
    }
    if (best < 0) continue;
    const int s = labelAt(labels, pixel);
    if (s < 0 || s >= count) continue;
    if (e_mover + options.intensity_margin < e_static)
      votes.push_back({s, best}), ++mover_tally[best];
    else if (e_static + options.intensity_margin < e_mover)
      votes.push_back({s, -1 - best}), ++static_tally[best];
  }
  // A mover must explain the samples around its own points better than the static world does; a motion fitted to
  // a real sensor's structured errors (TUM fr2/desk: the near desk at the image bottom, where depth and colour were
  // taken ~20 ms apart) does not, and its votes are dropped.
  std::vector<bool> kept_mover(out.movers.size());
  for (std::size_t m = 0; m < out.movers.size(); ++m) kept_mover[m] = mover_tally[m] > static_tally[m];
  for (const RigidSampleVote& vote : votes) {
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
