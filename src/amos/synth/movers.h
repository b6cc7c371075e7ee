#pragma once
// Movers: everything that moves in a sequence, each with an instance id (1, 2, ...) written to the masks.
// People (class "person": a detector knows them) walk along paths or sit and shift; objects (class "object":
// no detector knows them, the case the paper's geometric stage exists for) are a box pushed across the floor,
// an office chair that rolls, a door that swings. A mover's geometry is a pure function of time.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "amos/synth/path_motion.h"
#include "amos/synth/person.h"
#include "amos/synth/scene.h"

namespace amos::synth {

struct InstanceInfo {
  std::uint16_t id = 0;
  std::string category;  // "person" or "object"
  std::string name;
};

class Mover {
 public:
  explicit Mover(InstanceInfo info) : info_(std::move(info)) {}
  virtual ~Mover() = default;
  const InstanceInfo& info() const { return info_; }
  // Appends the geometry at time t (seconds since the first frame), every primitive tagged with info().id.
  // Cut-out people turn towards camera_position_w.
  virtual void addGeometry(double t, const Eigen::Vector3d& camera_position_w, SceneGeometry& out) const = 0;

 private:
  InstanceInfo info_;
};

class WalkingPerson : public Mover {
 public:
  WalkingPerson(InstanceInfo info, PersonLook look, PingPongPath path);
  void addGeometry(double t, const Eigen::Vector3d& camera_position_w, SceneGeometry& out) const override;

 private:
  PersonLook look_;
  PingPongPath path_;
};

// Sits on a seat facing `heading` and shifts: leans, twists, turns the head, gestures, rolls a little.
class SittingPerson : public Mover {
 public:
  SittingPerson(InstanceInfo info, PersonLook look, Eigen::Vector2d seat, double heading, double seat_height,
                std::uint32_t seed);
  void addGeometry(double t, const Eigen::Vector3d& camera_position_w, SceneGeometry& out) const override;

 private:
  PersonLook look_;
  Eigen::Vector2d seat_;
  double heading_, seat_height_;
  double phase_[6];
};

// Rigid geometry (in its own floor frame) carried along a path: the pushed box and the rolling chair.
class SlidingObject : public Mover {
 public:
  // spin: extra yaw in radians per metre travelled (a chair turning as it rolls); yaw0: yaw at rest.
  SlidingObject(InstanceInfo info, SceneGeometry local_geometry, PingPongPath path, double yaw0, double spin);
  void addGeometry(double t, const Eigen::Vector3d& camera_position_w, SceneGeometry& out) const override;

 private:
  SceneGeometry geometry_;
  PingPongPath path_;
  double yaw0_, spin_;
};

// Door leaf (furniture.h doorLeaf frame) hinged at `hinge`; closed it points along closed_yaw, and it opens by
// up to open_angle (positive = anticlockwise seen from above) in a cycle: closed, opening, open, closing.
class SwingingDoor : public Mover {
 public:
  SwingingDoor(InstanceInfo info, SceneGeometry leaf, Eigen::Vector3d hinge, double closed_yaw, double open_angle,
               double period_s, double start_offset_s);
  void addGeometry(double t, const Eigen::Vector3d& camera_position_w, SceneGeometry& out) const override;
  double angleAt(double t) const;

 private:
  SceneGeometry leaf_;
  Eigen::Vector3d hinge_;
  double closed_yaw_, open_angle_, period_, offset_;
};

// A person who looks like one except within [from_s, to_s), when the same walk is made in `disguise` (a plain suit
// from head to foot, no face): a person detector misses them there (issue 55: a mask that fails for some frames).
class DisguisedPerson : public Mover {
 public:
  DisguisedPerson(InstanceInfo info, PersonLook look, PersonLook disguise, PingPongPath path, double from_s,
                  double to_s);
  void addGeometry(double t, const Eigen::Vector3d& camera_position_w, SceneGeometry& out) const override;

 private:
  WalkingPerson plain_, disguised_;
  double from_, to_;
};

// A mover that moves only within a time window [begin_s, end_s]: before it, it stands as the inner mover stands at
// begin_s; after it, as at end_s. Movers that change state (issue 16): an object that rests and then is pushed
// (start-moving), one that is pushed and then stays (stop-moving).
class ScheduledMover : public Mover {
 public:
  ScheduledMover(std::unique_ptr<Mover> inner, double begin_s, double end_s);
  void addGeometry(double t, const Eigen::Vector3d& camera_position_w, SceneGeometry& out) const override;

 private:
  std::unique_ptr<Mover> inner_;
  double begin_, end_;
};

}  // namespace amos::synth
