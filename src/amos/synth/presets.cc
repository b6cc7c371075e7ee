#include "amos/synth/presets.h"

#include <algorithm>

#include "amos/core/error.h"

namespace amos::synth {

bool Preset::hasMover(MoverKind kind) const { return std::find(movers.begin(), movers.end(), kind) != movers.end(); }

const std::vector<Preset>& allPresets() {
  using M = MoverKind;
  using C = CameraMotion;
  static const std::vector<Preset> presets = {
      {"static_still",
       "static room, hand-held camera held still (path of walking_static)",
       C::kStatic,
       300,
       {},
       "static_still"},
      {"static_xyz",
       "static room, camera moving along x/y/z (path of walking_xyz, sitting_xyz, box_push, box_starts, box_stops, "
       "chair_push)",
       C::kXyz,
       300,
       {},
       "static_xyz"},
      {"static_rpy",
       "static room, camera rotating about roll/pitch/yaw (path of walking_rpy)",
       C::kRpy,
       300,
       {},
       "static_rpy"},
      {"static_halfsphere",
       "static room, camera on a 1 m half sphere (path of walking_halfsphere)",
       C::kHalfsphere,
       300,
       {},
       "static_halfsphere"},
      {"static_loop",
       "static room, 20 s room-scale loop that closes (path of walking_loop)",
       C::kLoop,
       600,
       {},
       "static_loop"},
      {"covered_halfsphere",
       "static room, path of static_halfsphere, lens covered from 5 to 7 s (black, no depth) while the camera moves on",
       C::kHalfsphere,
       360,
       {},
       "static_halfsphere",
       5.0,
       7.0},
      {"walking_static",
       "two people walking, camera held still",
       C::kStatic,
       300,
       {M::kWalkerAcross, M::kWalkerAround},
       "static_still"},
      {"walking_xyz",
       "two people walking, camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kWalkerAcross, M::kWalkerAround},
       "static_xyz"},
      {"walking_rpy",
       "two people walking, camera rotating",
       C::kRpy,
       300,
       {M::kWalkerAcross, M::kWalkerAround},
       "static_rpy"},
      {"walking_halfsphere",
       "two people walking, camera on a half sphere",
       C::kHalfsphere,
       300,
       {M::kWalkerAcross, M::kWalkerAround},
       "static_halfsphere"},
      {"walking_loop",
       "two people walking, camera on the room-scale loop",
       C::kLoop,
       600,
       {M::kWalkerAcross, M::kWalkerAround},
       "static_loop"},
      {"sitting_xyz",
       "two people sitting at the desk and shifting, camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kSitterLeft, M::kSitterRight},
       "static_xyz"},
      {"box_push",
       "a box pushed across the floor (no person), camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kPushedBox},
       "static_xyz"},
      {"objects_xyz",
       "pushed box, rolling chair and swinging door (no person), camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kPushedBox, M::kRollingChair, M::kSwingingDoor},
       "objects_xyz --no-movers"},
      {"box_starts",
       "a box at rest for 4 s, then pushed 2 m across the floor and at rest again, camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kBoxStarts},
       "static_xyz"},
      {"box_stops",
       "a box pushed 2 m across the floor from the first frame, at rest from 4 s on, camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kBoxStops},
       "static_xyz"},
      {"chair_push",
       "a person pushing an office chair 1.6 m from 3 s on, both at rest before and after, camera moving along "
       "x/y/z",
       C::kXyz,
       300,
       {M::kChairPush},
       "static_xyz"},
      // Issue 55: the scenes where the dynamic masks fail, for free-space carving (docs/synthetic.md).
      {"standing_leaves",
       "a person standing still in the middle of the view for 1.5 s, then walking out of it at 1.2 m/s, camera "
       "moving along x/y/z",
       C::kXyz,
       300,
       {M::kStandingLeaves},
       "static_xyz"},
      {"disguised_walker",
       "the walker across, in a plain suit without a face from 0.6 to 2.4 s (a person detector misses them), "
       "camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kDisguisedWalker},
       "static_xyz"},
      {"border_walker",
       "a person walking to and fro along the left edge of the view, half in it, camera moving along x/y/z",
       C::kXyz,
       300,
       {M::kBorderWalker},
       "static_xyz"},
  };
  return presets;
}

const Preset& findPreset(const std::string& name) {
  std::string names;
  for (const Preset& p : allPresets()) {
    if (p.name == name) return p;
    names += (names.empty() ? "" : ", ") + p.name;
  }
  throw core::Error("unknown synth preset '" + name + "' (known: " + names + ")");
}

}  // namespace amos::synth
