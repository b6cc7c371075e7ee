#include "amos/match/matching_options.h"

#include <string>

#include "amos/core/error.h"

namespace amos::match {

void MatchingOptions::check() const {
  core::require(th_high > 0 && th_high <= 256, "Matching.thHigh must be in (0, 256], got " + std::to_string(th_high));
  core::require(th_low > 0 && th_low <= th_high, "Matching.thLow must be in (0, thHigh], got " + std::to_string(th_low));
  core::require(local_ratio > 0 && local_ratio <= 1, "Matching.localRatio must be in (0, 1]");
  core::require(brute_force_ratio > 0 && brute_force_ratio <= 1, "Matching.bruteForceRatio must be in (0, 1]");
}

}  // namespace amos::match
