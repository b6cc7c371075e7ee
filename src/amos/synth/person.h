#pragma once
// People: upright figures that walk or sit. Two looks:
//  - procedural: an articulated body of cylinders and spheres (legs, pelvis, torso, arms, neck, head with a
//    face) in procedural clothes, with a walking gait (hip and knee swing, arm swing, feet on the floor);
//  - cut-out: a billboard carrying a real person photograph (RGB + mask), turned towards the camera, so that a
//    real person detector finds it. A cut-out cut by the photo's bottom border stands on procedural legs.
// Every primitive of one person carries the person's instance id.
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>

#include "amos/synth/furniture.h"
#include "amos/synth/scene.h"

namespace amos::synth {

struct PersonCutout;  // image_assets.h

struct PersonLook {
  double height = 1.75;  // standing height in metres
  // Procedural look.
  Surface shirt, trousers, skin, head, shoes;
  // Cut-out look (used when cutout.texture >= 0).
  Surface cutout;
  double cutout_aspect = 0.4;    // width / height of the cut-out image
  double cutout_fraction = 1.0;  // part of the standing height the cut-out shows from the top of the head
  bool cutout_sitting = false;   // the photo shows a seated person (feet on the floor)
  bool usesCutout() const { return cutout.texture >= 0; }
};

PersonLook proceduralLook(AssetContext& ctx);
// Look from a person cut-out; its texture is added to the context's bank.
PersonLook cutoutLook(AssetContext& ctx, const PersonCutout& cutout);

// Pose of a person at one instant (world frame).
struct BodyPose {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // floor point under the hips
  double heading = 0;                                  // yaw the body faces (radians)
  double gait_phase = 0;                               // radians; one cycle = two steps
  double gait_amplitude = 0;                           // 0 standing still .. 1 walking
  bool sitting = false;
  double seat_height = 0.47;
  double lean = 0;       // torso pitch forwards (radians)
  double twist = 0;      // torso yaw relative to heading (radians)
  double head_turn = 0;  // head yaw relative to the torso (radians)
  double arm_raise = 0;  // 0 .. 1: the right forearm lifted in a gesture
};

// Appends the person's geometry. Cut-outs turn to face camera_position_w (about the vertical axis).
void addPerson(const PersonLook& look, const BodyPose& pose, const Eigen::Vector3d& camera_position_w,
               std::uint16_t instance, SceneGeometry& out);

}  // namespace amos::synth
