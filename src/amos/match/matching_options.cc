#include "amos/match/matching_options.h"

#include <fmt/format.h>
#include <string>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::match {

void MatchingOptions::check() const {
  core::requireOption(th_high > 0 && th_high <= 256, core::option(th_high, "th_high"),
                      fmt::format("must be in (0, 256], got {}", th_high));
  core::requireOption(th_low > 0 && th_low <= th_high, core::option(th_low, "th_low"),
                      fmt::format("must be in (0, th_high = {}], got {}", th_high, th_low),
                      {core::option(th_high, "th_high")});
  core::requireOption(local_ratio > 0 && local_ratio <= 1, core::option(local_ratio, "local_ratio"),
                      fmt::format("must be in (0, 1], got {}", local_ratio));
  core::requireOption(brute_force_ratio > 0 && brute_force_ratio <= 1,
                      core::option(brute_force_ratio, "brute_force_ratio"),
                      fmt::format("must be in (0, 1], got {}", brute_force_ratio));
}

}  // namespace amos::match
