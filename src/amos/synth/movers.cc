#include "amos/synth/movers.h"

#include <algorithm>
#include <cmath>

#include "amos/synth/random.h"

namespace amos::synth {

WalkingPerson::WalkingPerson(InstanceInfo info, PersonLook look, PingPongPath path)
    : Mover(std::move(info)), look_(std::move(look)), path_(std::move(path)) {}

void WalkingPerson::addGeometry(double t, const Eigen::Vector3d& camera, SceneGeometry& out) const {
  const TravelState s = path_.at(t);
  BodyPose pose;
  pose.position = s.position;
  pose.heading = s.heading;
  // One gait cycle (two steps) per 1.3 m; the legs close as the walker slows into a rest.
  pose.gait_phase = 2 * M_PI * s.distance / 1.3;
  pose.gait_amplitude = std::min(1.0, s.speed / 0.5);
  pose.head_turn = 0.3 * std::sin(0.7 * t);
  addPerson(look_, pose, camera, info().id, out);
}

DisguisedPerson::DisguisedPerson(InstanceInfo info, PersonLook look, PersonLook disguise, PingPongPath path,
                                 double from_s, double to_s)
    : Mover(info), plain_(info, std::move(look), path), disguised_(info, std::move(disguise), path), from_(from_s),
      to_(to_s) {}

void DisguisedPerson::addGeometry(double t, const Eigen::Vector3d& camera, SceneGeometry& out) const {
  (t >= from_ && t < to_ ? disguised_ : plain_).addGeometry(t, camera, out);
}

SittingPerson::SittingPerson(InstanceInfo info, PersonLook look, Eigen::Vector2d seat, double heading,
                             double seat_height, std::uint32_t seed)
    : Mover(std::move(info)),
      look_(std::move(look)),
      seat_(std::move(seat)),
      heading_(heading),
      seat_height_(seat_height) {
  Random rng(seed);
  for (double& p : phase_) p = rng.uniform(0, 2 * M_PI);
}

void SittingPerson::addGeometry(double t, const Eigen::Vector3d& camera, SceneGeometry& out) const {
  // Slow, small shifts as in TUM fr3/sitting: a few degrees of lean and twist, the head looking around, now and
  // then a gesture, the chair rolling by a few centimetres.
  BodyPose pose;
  pose.sitting = true;
  pose.seat_height = seat_height_;
  const double roll = 0.05 * std::sin(2 * M_PI * 0.03 * t + phase_[0]);
  const Eigen::Vector2d forward(std::cos(heading_), std::sin(heading_)), side(-forward.y(), forward.x());
  pose.position = seat_ + roll * side + 0.03 * std::sin(2 * M_PI * 0.05 * t + phase_[1]) * forward;
  pose.heading = heading_;
  pose.lean = 0.08 * std::sin(2 * M_PI * 0.07 * t + phase_[2]) + 0.04 * std::sin(2 * M_PI * 0.19 * t + phase_[3]);
  pose.twist = 0.25 * std::sin(2 * M_PI * 0.05 * t + phase_[4]);
  pose.head_turn = 0.45 * std::sin(2 * M_PI * 0.09 * t + phase_[5]);
  pose.arm_raise = std::pow(std::max(0.0, std::sin(2 * M_PI * 0.04 * t + phase_[0] + phase_[3])), 4);
  addPerson(look_, pose, camera, info().id, out);
}

SlidingObject::SlidingObject(InstanceInfo info, SceneGeometry local_geometry, PingPongPath path, double yaw0,
                             double spin)
    : Mover(std::move(info)), geometry_(std::move(local_geometry)), path_(std::move(path)), yaw0_(yaw0), spin_(spin) {
  for (Quad& q : geometry_.quads) q.instance = this->info().id;
  for (Cylinder& c : geometry_.cylinders) c.instance = this->info().id;
  for (Sphere& s : geometry_.spheres) s.instance = this->info().id;
}

void SlidingObject::addGeometry(double t, const Eigen::Vector3d&, SceneGeometry& out) const {
  const TravelState s = path_.at(t);
  // Pushed objects do not turn to face their direction of travel; they drift in yaw as they slide.
  const double yaw = yaw0_ + spin_ * std::sin(M_PI * s.distance / path_.length());
  out.append(transformed(geometry_, floorPose(s.position.x(), s.position.y(), yaw)));
}

SwingingDoor::SwingingDoor(InstanceInfo info, SceneGeometry leaf, Eigen::Vector3d hinge, double closed_yaw,
                           double open_angle, double period_s, double start_offset_s)
    : Mover(std::move(info)),
      leaf_(std::move(leaf)),
      hinge_(std::move(hinge)),
      closed_yaw_(closed_yaw),
      open_angle_(open_angle),
      period_(period_s),
      offset_(start_offset_s) {
  for (Quad& q : leaf_.quads) q.instance = this->info().id;
}

double SwingingDoor::angleAt(double t) const {
  // Cycle: closed 25%, opening 25%, open 20%, closing 30%, with smooth starts and stops.
  double f = std::fmod(t + offset_, period_) / period_;
  if (f < 0) f += 1;
  auto smooth = [](double x) { return 0.5 - 0.5 * std::cos(M_PI * std::clamp(x, 0.0, 1.0)); };
  double open;
  if (f < 0.25)
    open = 0;
  else if (f < 0.5)
    open = smooth((f - 0.25) / 0.25);
  else if (f < 0.7)
    open = 1;
  else
    open = 1 - smooth((f - 0.7) / 0.3);
  return open_angle_ * open;
}

void SwingingDoor::addGeometry(double t, const Eigen::Vector3d&, SceneGeometry& out) const {
  out.append(transformed(leaf_, floorPose(hinge_.x(), hinge_.y(), closed_yaw_ + angleAt(t), hinge_.z())));
}

ScheduledMover::ScheduledMover(std::unique_ptr<Mover> inner, double begin_s, double end_s)
    : Mover(inner->info()), inner_(std::move(inner)), begin_(begin_s), end_(std::max(begin_s, end_s)) {}

void ScheduledMover::addGeometry(double t, const Eigen::Vector3d& camera, SceneGeometry& out) const {
  inner_->addGeometry(std::clamp(t, begin_, end_), camera, out);
}

}  // namespace amos::synth
