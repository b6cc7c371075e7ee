#pragma once
// Named sequences. A preset is a camera motion plus a set of movers in the shared room; the room and the camera
// path depend only on the seed and the motion, so every dynamic preset has a static counterpart that flies the
// identical path through the identical room without movers (also reachable as `--no-movers`):
//   walking_static -> static_still      walking_xyz, sitting_xyz, box_push -> static_xyz
//   walking_rpy -> static_rpy           walking_halfsphere -> static_halfsphere      walking_loop -> static_loop
//   objects_xyz -> objects_xyz with --no-movers (its door is a mover, so the static room has an open doorway)
//   box_starts, box_stops, chair_push -> static_xyz
//   standing_leaves, disguised_walker, border_walker -> static_xyz (issue 55: where the dynamic masks fail)
#include <string>
#include <vector>

#include "amos/synth/camera_path.h"

namespace amos::synth {

enum class MoverKind {
  kWalkerAcross,  // person walking across in front of the desk, back and forth
  kWalkerAround,  // person walking round the desk and behind it (the desk hides the legs)
  kSitterLeft,    // person sitting behind the desk (left seat seen from the camera)
  kSitterRight,
  kPushedBox,     // cardboard box pushed across the floor (unknown object)
  kRollingChair,  // office chair rolling and turning (unknown object)
  kSwingingDoor,  // door in the back wall swinging open and shut (unknown object)
  kBoxStarts,     // box at rest for the first 4 s, then pushed 2 m across the floor, then at rest (start-moving)
  kBoxStops,      // box pushed 2 m from the first frame, at rest from 4 s on (stop-moving)
  kChairPush,     // a person pushing an office chair 1.6 m from 3 s on (paper Fig. 4 (c)-(d)): two instances,
                  // the person ("person", a prior object) and the chair ("object", which no detector knows)
  kStandingLeaves,   // a person standing still in the middle of the view for 1.5 s, then walking out of it
  kDisguisedWalker,  // the walker across, in a plain suit without a face from 0.6 to 2.4 s (the detector misses)
  kBorderWalker,     // a person walking along the left edge of the view, half in it
};

struct Preset {
  std::string name;
  std::string description;
  CameraMotion motion = CameraMotion::kStatic;
  int default_frames = 300;
  std::vector<MoverKind> movers;
  std::string static_counterpart;  // preset with the same camera path and room and no movers
  // The lens is covered during [covered_from_s, covered_to_s): black image and no depth, while the camera goes on
  // along its path (tests relocalisation after a loss). Not covered when from >= to.
  double covered_from_s = 0, covered_to_s = 0;

  bool hasMover(MoverKind kind) const;
  bool coveredAt(double t) const { return t >= covered_from_s && t < covered_to_s; }
};

const std::vector<Preset>& allPresets();
// Throws core::Error listing the known names when `name` is not one.
const Preset& findPreset(const std::string& name);

}  // namespace amos::synth
