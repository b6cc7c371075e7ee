#include "amos/synth/path_motion.h"

#include <algorithm>
#include <cmath>

#include "amos/core/error.h"

namespace amos::synth {

PingPongPath::PingPongPath(std::vector<Eigen::Vector2d> waypoints, double speed, double rest_s, double ease,
                           double start_offset_s)
    : points_(std::move(waypoints)), speed_(speed), rest_(rest_s), ease_(ease), offset_(start_offset_s) {
  core::require(points_.size() >= 2, "PingPongPath needs at least two waypoints");
  core::require(speed > 0 && rest_s >= 0 && ease >= 0 && ease <= 1, "PingPongPath: invalid speed, rest or ease");
  cumulative_.push_back(0);
  for (std::size_t i = 1; i < points_.size(); ++i)
    cumulative_.push_back(cumulative_.back() + (points_[i] - points_[i - 1]).norm());
  length_ = cumulative_.back();
  core::require(length_ > 0, "PingPongPath: waypoints must not all coincide");
  travel_time_ = length_ / speed_;
}

Eigen::Vector2d PingPongPath::pointAt(double arc) const {
  arc = std::clamp(arc, 0.0, length_);
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), arc);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(it - cumulative_.begin()), points_.size() - 1);
  const double seg = cumulative_[i] - cumulative_[i - 1];
  const double f = seg > 0 ? (arc - cumulative_[i - 1]) / seg : 0;
  return points_[i - 1] + f * (points_[i] - points_[i - 1]);
}

double PingPongPath::headingAt(double arc, int direction) const {
  // Direction of travel smoothed over +-0.3 m, so that walkers round the corners.
  const double a = std::clamp(arc - 0.3, 0.0, length_), b = std::clamp(arc + 0.3, 0.0, length_);
  Eigen::Vector2d d = pointAt(b) - pointAt(a);
  if (direction < 0) d = -d;
  return std::atan2(d.y(), d.x());
}

TravelState PingPongPath::at(double t) const {
  const double cycle = 2 * (travel_time_ + rest_);
  double tc = std::fmod(t + offset_, cycle);
  if (tc < 0) tc += cycle;
  const double laps = std::floor((t + offset_) / cycle);
  TravelState s;
  // Phases: travel forwards, rest at the end, travel back, rest at the start.
  auto eased = [&](double tau) { return (1 - ease_) * tau + ease_ * (tau - std::sin(2 * M_PI * tau) / (2 * M_PI)); };
  auto easedRate = [&](double tau) { return (1 - ease_) + ease_ * (1 - std::cos(2 * M_PI * tau)); };
  if (tc < travel_time_) {
    const double tau = tc / travel_time_;
    const double arc = length_ * eased(tau);
    s.position = pointAt(arc);
    s.heading = headingAt(arc, +1);
    s.speed = speed_ * easedRate(tau);
    s.leg_progress = tau;
    s.distance = arc;
  } else if (tc < travel_time_ + rest_) {
    const double f = (tc - travel_time_) / std::max(rest_, 1e-9);
    s.position = points_.back();
    // Turn round on the spot: from arriving (+1) to leaving (-1) over the rest.
    const double h0 = headingAt(length_, +1), h1 = headingAt(length_, -1);
    double dh = std::remainder(h1 - h0, 2 * M_PI);
    s.heading = h0 + dh * (0.5 - 0.5 * std::cos(M_PI * f));
    s.resting = true;
    s.distance = length_;
  } else if (tc < 2 * travel_time_ + rest_) {
    const double tau = (tc - travel_time_ - rest_) / travel_time_;
    const double arc = length_ * (1 - eased(tau));
    s.position = pointAt(arc);
    s.heading = headingAt(arc, -1);
    s.speed = speed_ * easedRate(tau);
    s.leg_progress = tau;
    s.distance = length_ + length_ * eased(tau);
  } else {
    const double f = (tc - 2 * travel_time_ - rest_) / std::max(rest_, 1e-9);
    s.position = points_.front();
    const double h0 = headingAt(0, -1), h1 = headingAt(0, +1);
    double dh = std::remainder(h1 - h0, 2 * M_PI);
    s.heading = h0 + dh * (0.5 - 0.5 * std::cos(M_PI * f));
    s.resting = true;
    s.distance = 2 * length_;
  }
  s.distance += laps * 2 * length_;
  return s;
}

}  // namespace amos::synth
