#pragma once
// The furnished room every preset plays in: 7 m x 6 m x 2.7 m (x in [-3.5, 3.5], y in [-3, 3], floor at z = 0),
// walls, floor and ceiling each with their own non-repeating texture, a desk with monitors facing the camera
// stage, office chairs, shelves, boxes, a sofa, a second desk, plants and a door. Built from one seed; the
// movers never change it (except that a swinging door replaces the static closed one).
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "amos/synth/camera_path.h"
#include "amos/synth/renderer.h"
#include "amos/synth/scene.h"
#include "amos/synth/texture.h"

namespace amos::synth {

struct RoomOptions {
  double metres_per_texel = 0.004;  // texel size of walls, floor and ceiling (props get half of it)
  bool door_is_mover = false;       // leave the door leaf out: a SwingingDoor mover draws it
  void check() const;
};

// Where things are, for the camera paths and the movers.
struct RoomLayout {
  Eigen::Vector2d half_extent{3.5, 3.0};
  double height = 2.7;
  CameraStage stage;
  Eigen::Vector2d desk_centre{1.9, 0.0};
  Eigen::Vector2d desk_size{0.8, 1.6};  // depth along x, width along y
  double desk_height = 0.75;
  // Chairs behind the desk (seat centres), facing -x towards the camera stage.
  std::vector<Eigen::Vector2d> seats{{2.65, 0.5}, {2.65, -0.5}};
  double seat_height = 0.47;
  // Door in the east wall (x = 3.5): hinge at y = door_hinge_y, leaf closed along +y.
  double door_hinge_y = 1.2, door_width = 0.9, door_height = 2.05;
};

struct Room {
  RoomLayout layout;
  SceneGeometry geometry;
  Lighting lighting;
};

// Adds the room's textures to `textures` and returns its static geometry.
Room buildRoom(const RoomOptions& options, std::uint32_t seed, TextureBank& textures,
               const std::vector<cv::Mat>& photos);

}  // namespace amos::synth
