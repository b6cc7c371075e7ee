#include "amos/eval/rpe.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "amos/core/error.h"
#include "amos/core/pose.h"
#include "amos/eval/associate.h"

namespace amos::eval {
namespace {

double medianOf(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

// Pair subset above max_pairs: a partial Fisher-Yates shuffle with a fixed seed, kept in time order.
std::vector<std::pair<std::size_t, std::size_t>> samplePairs(std::vector<std::pair<std::size_t, std::size_t>> pairs,
                                                            std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  for (std::size_t k = 0; k < count; ++k) {
    std::uniform_int_distribution<std::size_t> pick(k, pairs.size() - 1);
    std::swap(pairs[k], pairs[pick(rng)]);
  }
  pairs.resize(count);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

void RpeOptions::check() const {
  core::require(delta_s > 0, "eval.rpe_delta must be positive");
  core::require(std::isfinite(offset_s), "eval.time_offset must be finite");
  core::require(scale > 0, "RPE scale must be positive");
}

std::size_t findClosestIndex(const std::vector<double>& sorted, double t) {
  std::size_t begin = 0, end = sorted.size(), best = 0;
  double best_difference = std::abs(sorted[0] - t);
  while (begin < end) {
    const std::size_t middle = (begin + end) / 2;
    const double difference = std::abs(sorted[middle] - t);
    if (difference < best_difference) {
      best_difference = difference;
      best = middle;
    }
    if (sorted[middle] == t) return middle;
    if (sorted[middle] > t) {
      end = middle;
    } else {
      begin = middle + 1;
    }
  }
  return best;
}

RpeResult computeRpe(const std::vector<io::StampedPose>& gt_raw, const std::vector<io::StampedPose>& est_raw,
                     const RpeOptions& options) {
  options.check();
  const std::vector<io::StampedPose> gt = sortedUniqueByTimestamp(gt_raw);
  const std::vector<io::StampedPose> est = sortedUniqueByTimestamp(est_raw);
  RpeResult result;
  if (gt.size() < 2 || est.size() < 2) {
    result.trans_m = result.rot_deg = computeErrorStats({});
    return result;
  }
  const std::vector<double> gt_stamps = timestampsOf(gt);
  const std::vector<double> est_stamps = timestampsOf(est);

  // Pairs of estimated poses delta seconds apart.
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const std::size_t j = findClosestIndex(est_stamps, est_stamps[i] + options.delta_s);
    if (j != est.size() - 1) pairs.emplace_back(i, j);
  }
  if (options.max_pairs != 0 && pairs.size() > options.max_pairs) {
    pairs = samplePairs(std::move(pairs), options.max_pairs, options.seed);
  }

  std::vector<double> gt_intervals;
  for (std::size_t k = 1; k < gt_stamps.size(); ++k) gt_intervals.push_back(gt_stamps[k] - gt_stamps[k - 1]);
  const double gt_max_time_difference = 2.0 * medianOf(gt_intervals);

  std::vector<double> trans_errors, rot_errors_deg;
  for (const auto& [i, j] : pairs) {
    const double t_est_0 = est_stamps[i] + options.offset_s;
    const double t_est_1 = est_stamps[j] + options.offset_s;
    const std::size_t g0 = findClosestIndex(gt_stamps, t_est_0);
    const std::size_t g1 = findClosestIndex(gt_stamps, t_est_1);
    if (std::abs(gt_stamps[g0] - t_est_0) > gt_max_time_difference ||
        std::abs(gt_stamps[g1] - t_est_1) > gt_max_time_difference) {
      continue;
    }
    core::SE3 est_motion = est[j].T_wc.inverse() * est[i].T_wc;
    est_motion.translation() *= options.scale;
    const core::SE3 gt_motion = gt[g1].T_wc.inverse() * gt[g0].T_wc;
    const core::SE3 error = est_motion.inverse() * gt_motion;
    RpePair pair{est_stamps[i], est_stamps[j], gt_stamps[g0], gt_stamps[g1], error.translation().norm(),
                 core::rotationAngle(error)};
    trans_errors.push_back(pair.trans_error_m);
    rot_errors_deg.push_back(pair.rot_error_rad * 180.0 / M_PI);
    result.pairs.push_back(pair);
  }
  result.trans_m = computeErrorStats(trans_errors);
  result.rot_deg = computeErrorStats(rot_errors_deg);
  return result;
}

}  // namespace amos::eval
