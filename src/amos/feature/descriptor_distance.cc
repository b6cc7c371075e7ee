#include "amos/feature/descriptor_distance.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "amos/core/error.h"
#include "amos/core/popcnt_clones.h"

namespace amos::feature {

namespace {

// Four 64-bit words; memcpy keeps the loads free of alignment and aliasing assumptions (compiles to plain loads).
inline int distance256(const std::uint8_t* a, const std::uint8_t* b) {
  int distance = 0;
  for (int w = 0; w < 4; ++w) {
    std::uint64_t x, y;
    std::memcpy(&x, a + 8 * w, 8);
    std::memcpy(&y, b + 8 * w, 8);
    distance += __builtin_popcountll(x ^ y);
  }
  return distance;
}

struct Nearest {
  int best, second, best_train;
};

// Nearest and second nearest train row of every query row (the ratio test needs both).
AMOS_POPCNT_CLONES void nearestTwo(const cv::Mat& query, const cv::Mat& train, std::vector<Nearest>& out) {
  out.resize(static_cast<size_t>(query.rows));
  for (int q = 0; q < query.rows; ++q) {
    const std::uint8_t* dq = query.ptr<std::uint8_t>(q);
    int best = std::numeric_limits<int>::max(), second = std::numeric_limits<int>::max(), best_train = -1;
    for (int t = 0; t < train.rows; ++t) {
      const int d = distance256(dq, train.ptr<std::uint8_t>(t));
      if (d < best) {
        second = best;
        best = d;
        best_train = t;
      } else if (d < second) {
        second = d;
      }
    }
    out[static_cast<size_t>(q)] = {best, second, best_train};
  }
}

}  // namespace

AMOS_POPCNT_CLONES int hammingDistance(const std::uint8_t* a, const std::uint8_t* b) { return distance256(a, b); }

std::vector<BruteForceMatch> matchBruteForce(const cv::Mat& query, const cv::Mat& train, int max_distance,
                                             float ratio) {
  auto valid = [](const cv::Mat& m) { return m.empty() || (m.type() == CV_8UC1 && m.cols == 32); };
  core::require(valid(query) && valid(train), "matchBruteForce needs N x 32 CV_8U descriptor matrices");
  std::vector<BruteForceMatch> candidates;
  if (query.empty() || train.empty()) return candidates;

  std::vector<Nearest> nearest;
  nearestTwo(query, train, nearest);
  for (int q = 0; q < query.rows; ++q) {
    const Nearest& n = nearest[static_cast<size_t>(q)];
    if (n.best > max_distance) continue;
    // With a single train row there is no second neighbour and the ratio test passes.
    if (n.second != std::numeric_limits<int>::max() && !(n.best < ratio * n.second)) continue;
    candidates.push_back({q, n.best_train, n.best});
  }

  // One query per train row: the closest wins, ties go to the lower query index.
  std::vector<int> owner(static_cast<size_t>(train.rows), -1);
  for (size_t i = 0; i < candidates.size(); ++i) {
    int& o = owner[static_cast<size_t>(candidates[i].train)];
    if (o < 0 || candidates[i].distance < candidates[static_cast<size_t>(o)].distance) o = static_cast<int>(i);
  }
  std::vector<BruteForceMatch> matches;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (owner[static_cast<size_t>(candidates[i].train)] == static_cast<int>(i)) matches.push_back(candidates[i]);
  return matches;
}

}  // namespace amos::feature
