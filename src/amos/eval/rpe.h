#pragma once
// Relative pose error as the TUM benchmark's `evaluate_rpe.py --fixed_delta --delta <d> --delta_unit s`:
//   - estimated stamps sorted; for each i, j = findClosestIndex(stamps, t_i + delta); the pair (i, j) is kept
//     unless j is the last index (the script's rule, which also drops a genuine match with the last pose);
//   - above max_pairs pairs, a random subset of max_pairs is used (the script uses Python's random.sample with
//     seed 0; here std::mt19937 with `seed`, so the subset differs from the script's but is deterministic);
//   - each estimated stamp is matched to the closest ground-truth stamp (same binary search); the pair is
//     skipped when either match is further than 2 x the median ground-truth interval;
//   - error E = inv(inv(E_j) E_i) * inv(G_j) G_i with E, G the camera-to-world poses (the script's
//     ominus(ominus(E_j, E_i), ominus(G_j, G_i))); translational error |t(E)|, rotational error
//     arccos(clamp((trace(R(E)) - 1) / 2)).
// No alignment is involved: RPE is invariant to a rigid change of the world frame.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "amos/eval/stats.h"
#include "amos/io/trajectory.h"

namespace amos::eval {

struct RpeOptions {
  double delta_s = 1.0;            // eval.rpe_delta: time between the two poses of a pair, seconds
  std::size_t max_pairs = 10000;   // eval.rpe_max_pairs: 0 = use all pairs
  std::uint32_t seed = 0;          // eval.rpe_seed: for the subset drawn above max_pairs
  double offset_s = 0.0;           // eval.time_offset: added to estimated stamps before matching
  double scale = 1.0;              // multiplies the estimate's relative translations (script's --scale)
  void check() const;
};

struct RpePair {
  double est_stamp_0, est_stamp_1, gt_stamp_0, gt_stamp_1;
  double trans_error_m, rot_error_rad;
};

struct RpeResult {
  ErrorStats trans_m;    // translational error, metres
  ErrorStats rot_deg;    // rotational error, degrees
  std::vector<RpePair> pairs;  // in order of the first estimated stamp
};

// The script's find_closest_index on an ascending list: a binary search that remembers the closest element it
// visits (which is not always the globally closest one). `sorted` must not be empty.
std::size_t findClosestIndex(const std::vector<double>& sorted, double t);

// Inputs in any order; duplicate stamps keep the last pose. Returns zero pairs (NaN statistics) instead of
// throwing when nothing can be compared (e.g. an estimate shorter than delta); the script raises below 2 pairs.
RpeResult computeRpe(const std::vector<io::StampedPose>& gt, const std::vector<io::StampedPose>& est,
                     const RpeOptions& options = {});

}  // namespace amos::eval
