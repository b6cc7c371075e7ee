#include "amos/map/sensor.h"

#include <fmt/format.h>
#include <cmath>
#include <string>

#include "amos/core/error.h"
#include "amos/core/option_error.h"

namespace amos::map {

void SensorOptions::check() const {
  core::requireOption(bf > 0, core::option(bf, "bf"), fmt::format("must be > 0, got {}", bf));
  core::requireOption(th_depth > 0, core::option(th_depth, "th_depth"), fmt::format("must be > 0, got {}", th_depth));
}

Sensor::Sensor(const core::CameraIntrinsics& intrinsics, const SensorOptions& options,
               const feature::OrbOptions& orb)
    : camera_(intrinsics) {
  intrinsics.check();
  options.check();
  orb.check();
  bf_ = options.bf;
  close_depth_ = options.th_depth * options.bf / intrinsics.fx;
  scale_factor_ = static_cast<float>(orb.scale_factor);
  log_scale_factor_ = std::log(scale_factor_);
  scale_.resize(orb.num_levels);
  sigma2_.resize(orb.num_levels);
  inv_sigma2_.resize(orb.num_levels);
  for (int l = 0; l < orb.num_levels; ++l) {
    scale_[l] = static_cast<float>(std::pow(orb.scale_factor, l));
    sigma2_[l] = scale_[l] * scale_[l];
    inv_sigma2_[l] = 1.0f / sigma2_[l];
  }
  bounds_ = camera_.undistortedBounds();
}

}  // namespace amos::map
