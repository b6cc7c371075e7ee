#include "amos/dynamic/dynamic_options.h"

#include <fmt/format.h>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::dynamic {

DynamicMode parseDynamicMode(const std::string& text) {
  if (text == "none") return DynamicMode::kNone;
  if (text == "prior") return DynamicMode::kPrior;
  if (text == "geometry") return DynamicMode::kGeometry;
  if (text == "full") return DynamicMode::kFull;
  throw core::Error(fmt::format("Dynamic.mode must be one of none, prior, geometry, full; got '{}'", text));
}

std::string toString(DynamicMode mode) {
  switch (mode) {
    case DynamicMode::kNone:
      return "none";
    case DynamicMode::kPrior:
      return "prior";
    case DynamicMode::kGeometry:
      return "geometry";
    case DynamicMode::kFull:
      return "full";
  }
  return "unknown";
}

void DynamicOptions::check() const {
  superpixel.check();
  cluster.check();
  tracking.check();
  reprojection.check();
  epipolar.check();
  boundary.check();
  initial_pose.check();
  prior.check();
  depth.check();
  baseline_tracks.check();
  rigid_movers.check();
  core::requireOption(!baseline_tracks.enabled || depth.baseline_frames > 1,
                      core::option(baseline_tracks.enabled, "baseline_tracks.enabled"),
                      fmt::format("needs depth.baseline_frames > 1 (the frame it compares with), got {}",
                                  depth.baseline_frames),
                      {core::option(depth.baseline_frames, "depth.baseline_frames")});
  core::requireOption(prior_masked_extraction_coverage >= 0 && prior_masked_extraction_coverage <= 1,
                      core::option(prior_masked_extraction_coverage, "prior_masked_extraction_coverage"),
                      fmt::format("must be in [0, 1], got {}", prior_masked_extraction_coverage));
}

}  // namespace amos::dynamic
