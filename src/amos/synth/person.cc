#include "amos/synth/person.h"

#include <algorithm>
#include <cmath>

#include "amos/synth/image_assets.h"
#include "amos/synth/procedural_textures.h"

namespace amos::synth {

using Eigen::Vector3d;

namespace {

Eigen::Matrix3d personRotZ(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix(); }

// Direction in the body's sagittal plane at `angle` forwards from straight down.
Vector3d swingDir(double angle, double outward = 0) {
  return Vector3d(std::sin(angle), outward, -std::cos(angle)).normalized();
}

struct Legs {
  double hip_z = 0;
};

// Both legs (thighs, shins, feet) in the body frame; returns the hip height that keeps the lower foot on the floor.
// leg_scale shortens the legs (under a cut-out that already shows the thighs).
Legs addLegs(const PersonLook& look, const BodyPose& pose, double s, std::uint16_t id, SceneGeometry& g,
             double leg_scale = 1.0) {
  const double thigh = 0.44 * s * leg_scale, shin = 0.43 * s * leg_scale, foot_h = 0.07 * s, hip_half = 0.09 * s;
  const double A = pose.gait_amplitude;
  double theta[2], kappa[2], drop[2];
  for (int leg = 0; leg < 2; ++leg) {
    const double ph = pose.gait_phase + leg * M_PI;
    theta[leg] = 0.42 * A * std::sin(ph);
    // The knee bends most while the leg swings forwards (d theta / dt > 0).
    kappa[leg] = A * (0.05 + 0.7 * std::pow(std::max(0.0, std::cos(ph)), 1.5));
    drop[leg] = thigh * std::cos(theta[leg]) + shin * std::cos(theta[leg] - kappa[leg]);
  }
  Legs out;
  out.hip_z = std::max(drop[0], drop[1]) + foot_h;
  for (int leg = 0; leg < 2; ++leg) {
    const double side = leg == 0 ? 1.0 : -1.0;
    const Vector3d hip(0, side * hip_half, out.hip_z);
    const Vector3d knee = hip + thigh * swingDir(theta[leg]);
    const Vector3d ankle = knee + shin * swingDir(theta[leg] - kappa[leg]);
    g.addCylinder(hip, knee, 0.075 * s, look.trousers, id);
    g.addCylinder(knee, ankle, 0.058 * s, look.trousers, id);
    Eigen::Isometry3d foot = Eigen::Isometry3d::Identity();
    foot.translation() = ankle + Vector3d(0.06 * s, 0, -foot_h / 2);
    g.addBox(foot, {0.26 * s, 0.1 * s, foot_h}, allFaces(look.shoes), id);
  }
  return out;
}

// Pelvis, torso, arms, neck and head above the hips, in the body frame.
void addUpperBody(const PersonLook& look, const BodyPose& pose, double s, double hip_z, std::uint16_t id,
                  SceneGeometry& g) {
  const Eigen::Matrix3d twist = personRotZ(pose.twist);
  const double lean = pose.lean + (pose.sitting ? -0.08 : 0.04 * pose.gait_amplitude);
  const Vector3d axis = twist * Vector3d(std::sin(lean), 0, std::cos(lean));
  const Vector3d front = twist * Vector3d(std::cos(lean), 0, -std::sin(lean));
  const Vector3d left = axis.cross(front).normalized();
  g.addCylinder(Vector3d(0, 0, hip_z - 0.06 * s), Vector3d(0, 0, hip_z + 0.1 * s), 0.16 * s, look.trousers, id, front);
  const Vector3d base(0, 0, hip_z + 0.08 * s);
  const Vector3d shoulders = base + 0.47 * s * axis;
  g.addCylinder(base, shoulders + 0.04 * s * axis, 0.17 * s, look.shirt, id, front);
  const Vector3d neck_top = shoulders + 0.11 * s * axis;
  g.addCylinder(shoulders, neck_top, 0.05 * s, look.skin, id, front);
  g.addSphere(neck_top + 0.1 * s * axis, 0.105 * s, look.head, id,
              personRotZ(pose.twist + pose.head_turn) * Vector3d::UnitX(), axis);
  for (int arm = 0; arm < 2; ++arm) {
    const double side = arm == 0 ? 1.0 : -1.0;
    double upper_angle, elbow;
    if (pose.sitting) {  // forearms forwards, towards the desk
      upper_angle = 0.45;
      elbow = 1.0;
    } else {  // swing opposite to the leg on the same side
      upper_angle = -0.35 * pose.gait_amplitude * std::sin(pose.gait_phase + arm * M_PI);
      elbow = 0.2 + 0.25 * pose.gait_amplitude * std::max(0.0, -std::sin(pose.gait_phase + arm * M_PI));
    }
    if (arm == 1) {  // gesture with the right arm
      upper_angle += 0.9 * pose.arm_raise;
      elbow += 1.1 * pose.arm_raise;
    }
    const Vector3d shoulder = shoulders - 0.02 * s * axis + side * 0.22 * s * left;
    auto dir = [&](double a) {
      // In the torso frame: forwards by `a` from hanging down, slightly away from the body.
      return (std::sin(a) * front - std::cos(a) * axis + side * 0.08 * left).normalized();
    };
    const Vector3d elbow_p = shoulder + 0.29 * s * dir(upper_angle);
    const Vector3d wrist = elbow_p + 0.26 * s * dir(upper_angle + elbow);
    g.addCylinder(shoulder, elbow_p, 0.048 * s, look.shirt, id, front);
    g.addCylinder(elbow_p, wrist, 0.04 * s, look.skin, id, front);
    g.addSphere(wrist + 0.04 * s * dir(upper_angle + elbow), 0.045 * s, look.skin, id);
  }
}

void addSeatedLegs(const PersonLook& look, double s, double hip_z, std::uint16_t id, SceneGeometry& g) {
  const double foot_h = 0.07 * s;
  for (double side : {-1.0, 1.0}) {
    const Vector3d hip(0, side * 0.1 * s, hip_z);
    const Vector3d knee(0.44 * s, side * 0.12 * s, hip_z + 0.02 * s);
    const Vector3d ankle(0.5 * s, side * 0.12 * s, foot_h);
    g.addCylinder(hip, knee, 0.075 * s, look.trousers, id);
    g.addCylinder(knee, ankle, 0.058 * s, look.trousers, id);
    Eigen::Isometry3d foot = Eigen::Isometry3d::Identity();
    foot.translation() = ankle + Vector3d(0.06 * s, 0, -foot_h / 2);
    g.addBox(foot, {0.26 * s, 0.1 * s, foot_h}, allFaces(look.shoes), id);
  }
}

void addBillboard(const PersonLook& look, const BodyPose& pose, const Vector3d& camera, std::uint16_t id,
                  SceneGeometry& g) {
  const double H = look.height;
  Vector3d p(pose.position.x(), pose.position.y(), 0);
  Eigen::Vector2d v = (camera.head<2>() - pose.position);
  if (v.norm() < 1e-6) v = Eigen::Vector2d(std::cos(pose.heading), std::sin(pose.heading));
  v.normalize();
  // Sitting people turn a little with their torso twist; the billboard turns with them.
  const double turn = pose.sitting ? 0.5 * pose.twist : 0.0;
  v = Eigen::Rotation2Dd(turn) * v;
  const Vector3d right(-v.y(), v.x(), 0);
  double top, bottom, repeat_v = 1.0, width;
  if (pose.sitting) {
    if (look.cutout_sitting) {  // the photo shows the whole seated person
      top = 0.74 * H;
      bottom = 0;
      width = look.cutout_aspect * top;
    } else {  // a standing photo: show its top part, the desk hides the rest
      const double shown = std::min(look.cutout_fraction, 0.5);
      repeat_v = shown / look.cutout_fraction;
      top = 0.74 * H;
      bottom = top - shown * H;
      width = look.cutout_aspect * look.cutout_fraction * H;
    }
    p += Vector3d(v.x(), v.y(), 0) * (0.15 + 0.3 * pose.lean);  // in front of the seat, leaning with the body
  } else {
    const double bob = 0.015 * pose.gait_amplitude * std::abs(std::sin(pose.gait_phase));
    top = H + bob;
    bottom = H * (1 - look.cutout_fraction) + bob;
    width = look.cutout_aspect * look.cutout_fraction * H;
  }
  Quad q;
  q.origin = p + Vector3d(0, 0, top) - right * (width / 2);
  q.edge_u = right * width;
  q.edge_v = Vector3d(0, 0, -(top - bottom));
  q.surface = look.cutout;
  q.surface.alpha_test = true;
  q.surface.repeat_v = repeat_v;
  q.instance = id;
  g.quads.push_back(q);
}

}  // namespace

PersonLook proceduralLook(AssetContext& ctx) {
  PersonLook look;
  look.height = ctx.rng.uniform(1.62, 1.88);
  look.shirt = ctx.add(textures::shirt(cv::Size(256, 256), ctx.rng));
  look.trousers = ctx.add(textures::trousers(cv::Size(128, 256), ctx.rng));
  const cv::Mat skin = textures::skin(cv::Size(512, 256), ctx.rng, true);
  look.head = ctx.add(skin);
  look.skin = ctx.add(skin(cv::Rect(230, 180, 40, 40)).clone());  // plain skin from the cheek
  look.shoes = ctx.add(textures::metal(cv::Size(32, 32), cv::Scalar(30, 30, 35), ctx.rng));
  return look;
}

PersonLook cutoutLook(AssetContext& ctx, const PersonCutout& cutout) {
  PersonLook look = proceduralLook(ctx);  // legs and shoes for cut-outs that need them
  look.height = ctx.rng.uniform(1.7, 1.85);
  look.cutout.texture = ctx.textures.add(Texture(cutout.bgr, cutout.alpha, false));
  look.cutout_aspect = cutout.bgr.cols / static_cast<double>(cutout.bgr.rows);
  look.cutout_fraction = cutout.visible_fraction;
  look.cutout_sitting = cutout.kind == PersonCutout::Kind::kSitting;
  // Trousers in the colour of the photo's lowest visible rows, so the legs continue the person.
  cv::Mat legs = textures::trousers(cv::Size(128, 256), ctx.rng);
  const cv::Scalar mean = cv::mean(legs);
  legs.convertTo(legs, CV_8UC3, 1.0, 0);
  for (int y = 0; y < legs.rows; ++y)
    for (int x = 0; x < legs.cols; ++x)
      for (int c = 0; c < 3; ++c)
        legs.at<cv::Vec3b>(y, x)[c] =
            cv::saturate_cast<uchar>(legs.at<cv::Vec3b>(y, x)[c] * (cutout.lower_colour[c] + 1) / (mean[c] + 1));
  look.trousers = ctx.add(legs);
  return look;
}

void addPerson(const PersonLook& look, const BodyPose& pose, const Vector3d& camera_position_w, std::uint16_t id,
               SceneGeometry& out) {
  const double s = look.height / 1.75;
  if (look.usesCutout()) {
    addBillboard(look, pose, camera_position_w, id, out);
    if (!pose.sitting && look.cutout_fraction < 0.999) {
      // Legs from the floor to just above the photo's lower edge.
      const double photo_bottom = look.height * (1 - look.cutout_fraction);
      const double leg_scale = std::clamp((photo_bottom + 0.04 - 0.07 * s) / (0.87 * s), 0.2, 1.0);
      SceneGeometry legs;
      addLegs(look, pose, s, id, legs, leg_scale);
      out.append(transformed(legs, floorPose(pose.position.x(), pose.position.y(), pose.heading)));
    }
    return;
  }
  SceneGeometry body;
  double hip_z;
  if (pose.sitting) {
    hip_z = pose.seat_height + 0.07 * s;
    addSeatedLegs(look, s, hip_z, id, body);
  } else {
    hip_z = addLegs(look, pose, s, id, body).hip_z;
  }
  addUpperBody(look, pose, s, hip_z, id, body);
  out.append(transformed(body, floorPose(pose.position.x(), pose.position.y(), pose.heading)));
}

}  // namespace amos::synth
