#pragma once
// Settings of the dense static map (`run --dense`, the Dense.* keys of dense_keys.h; docs/dense.md says why each
// default is what it is). Header-only so that the settings can be read whether or not the dense module itself is
// built (it needs Open3D: AMOS_WITH_OPEN3D).
//
// The defaults follow the depth sensor's noise. Structured-light sensors (Kinect v1, Xtion: TUM, Bonn) measure depth
// with sigma(z) ~ 1.5 mm + 1.5e-3 * (z - 0.4)^2 m (Nguyen, Izadi, Lovell 2012): 5 mm at 2 m, 12 mm at 3 m, 21 mm at
// 4 m. A voxel of 2 cm is about 2 sigma at 3 m, where most of a room is seen from; the truncation band must hold the
// surface's noise on both sides (3 sigma at the farthest depth fused), 6 cm = 3 sigma at 4 m, so maxDepth = 4 m.
// Beyond it a reading's noise is larger than the band and would blur the surface it lands on.
#include <algorithm>
#include <cmath>

#include "amos/core/camera.h"
#include "amos/core/option_error.h"

namespace amos::dense {

struct DenseOptions {
  double voxel_size = 0.02;   // Dense.voxelSize: edge of a TSDF voxel (m)
  double truncation = 0.06;   // Dense.truncation: half-width of the signed-distance band (m), >= 2 voxels
  double min_depth = 0.3;     // Dense.minDepth: readings nearer than this are not fused (m; the sensor's own limit)
  double max_depth = 4.0;     // Dense.maxDepth: readings farther are not fused (m)
  // Dense.maskMargin: the dynamic mask grows by this many pixels (full resolution) before fusion: a mask's border
  // is uncertain and the depth at a person's silhouette mixes person and background. 10 px = 4 cm at 2 m.
  int mask_margin_px = 10;
  // Dense.edgeJump: a pixel whose 3x3 neighbourhood spans a depth step above edgeJump x depth lies on a depth
  // discontinuity ("flying pixels" between foreground and background): left out. 0.05 = 10 cm at 2 m, 13 sigma,
  // while a wall seen at 80 degrees steps by 1 % between neighbours.
  double edge_jump = 0.05;
  int edge_margin_px = 2;     // Dense.edgeMargin: ... and this many pixels around it
  // Dense.scale: depth and colour are fused at this fraction of the image size. At 0.5 a pixel covers z / (f / 2),
  // 7 mm at 2 m with f = 540, finer than a voxel up to 5 m, and the kept frames take a quarter of the memory.
  double scale = 0.5;
  int frame_step = 1;         // Dense.frameStep: every frameStep-th tracked frame is kept and fused
  // Dense.liveEvery: the live volume (the live view's cloud; poses as tracked) fuses every liveEvery-th kept
  // frame; the final map is fused anew from every kept frame with the final trajectory. 0 = no live volume.
  int live_every = 5;
  int queue_frames = 64;      // Dense.queueFrames: frames waiting for the fusion thread at most (then dropped)
  double live_cloud_voxel = 0.05;  // Dense.liveCloudVoxel: the live cloud handed to the viewer is downsampled to this
  double live_period_s = 1.0;      // Dense.livePeriod: seconds between two live clouds at least
  // The occupancy grid (ROS map_server format): cells of gridResolution, occupied where the map has surface between
  // gridMinHeight and gridMaxHeight above the floor (obstacles a robot meets), free where the floor was seen and
  // nothing stands on it, unknown elsewhere.
  double grid_resolution = 0.05;   // Dense.gridResolution (m)
  double grid_min_height = 0.10;   // Dense.gridMinHeight (m above the floor)
  double grid_max_height = 1.80;   // Dense.gridMaxHeight (m above the floor)
  // Free-space carving in the final fusion (free_space_carving.h, see_through.h): a surface point that later
  // frames see through (their reading beyond it by more than truncation + carveSigmas x the depth noise at that
  // range, in at least carveMinVotes frames and more often than a reading supports it, or in the last
  // carveRecentVotes frames that voted) is forgotten.
  bool carve = true;               // Dense.carve
  // Dense.carveSigmas: 3 sigma leave a static surface's noise in the band (0.3 % of the readings beyond it).
  double carve_sigmas = 3.0;
  // Dense.carveMinVotes: a tenth of a second at 30 Hz; a single noisy frame or flying pixel never carves.
  int carve_min_votes = 3;
  // Dense.carveRecentVotes: half a second at 30 Hz of frames that all look through a point since it was last seen
  // carve it even when it was seen more often before (a person who stood still, then left). 0 = majority alone.
  int carve_recent_votes = 15;

  // The structured-light sensors' depth noise at `z` metres (above): 1.5 mm + 1.5e-3 (z - 0.4)^2.
  static double depthNoise(double z) { return 0.0015 + 0.0015 * (z - 0.4) * (z - 0.4); }
  // What the voxels of the surface's band within maxDepth of one place take (the sphere a turning camera sees, 4 pi
  // maxDepth^2 of surface, 2 truncation thick, 32 bytes a voxel with its colour and weight): a bound on the volume
  // of a room-sized map, not a measure of a long walk's.
  double roomVolumeBytes() const {
    const double surface_m2 = 4 * 3.14159265358979 * max_depth * max_depth;
    return surface_m2 / (voxel_size * voxel_size) * (2 * truncation / voxel_size) * 32;
  }
  static constexpr double kMaxRoomVolumeBytes = 8e9;  // a third of the machines' 24 GB

  // Throws core::InvalidOption naming the member at fault. Each bound follows from what the key means.
  void check() const {
    using core::option;
    core::requireInRange(min_depth, "min_depth", 0.1, 10.0);  // no RGB-D sensor measures nearer than 10 cm
    core::requireOption(max_depth > min_depth && max_depth <= 20, option(max_depth, "max_depth"),
                        fmt::format("must be > min_depth ({}) and <= 20 m (no depth sensor's range), got {}",
                                    min_depth, max_depth),
                        {option(min_depth, "min_depth")});
    // A voxel finer than the depth noise at the nearest range resolves only noise; one coarser than half a metre
    // cannot hold a room's furniture.
    const double finest = depthNoise(min_depth);
    core::requireOption(std::isfinite(voxel_size) && voxel_size >= finest && voxel_size <= 0.5,
                        option(voxel_size, "voxel_size"),
                        fmt::format("must be in [{:.4f}, 0.5] m (the sensor's depth noise at min_depth, {:.1f} mm, "
                                    "resolves nothing finer), got {}",
                                    finest, 1000 * finest, voxel_size),
                        {option(min_depth, "min_depth")});
    core::requireOption(truncation >= 2 * voxel_size && truncation <= 1.0, option(truncation, "truncation"),
                        fmt::format("must be >= 2 x voxel_size ({}) and <= 1 m, got {}", 2 * voxel_size, truncation),
                        {option(voxel_size, "voxel_size")});
    core::requireOption(roomVolumeBytes() <= kMaxRoomVolumeBytes, option(voxel_size, "voxel_size"),
                        fmt::format("with truncation {} and max_depth {}: a room's volume would take {:.0f} GB (more "
                                    "than {:.0f} GB of memory), got {}",
                                    truncation, max_depth, roomVolumeBytes() / 1e9, kMaxRoomVolumeBytes / 1e9,
                                    voxel_size),
                        {option(truncation, "truncation"), option(max_depth, "max_depth")});
    // Margins in full-resolution pixels; against the image's size when the camera is known (frame_preparation.h).
    core::requireInRange(mask_margin_px, "mask_margin_px", 0, 1000);
    core::requireOption(edge_jump > 0 && edge_jump <= 1, option(edge_jump, "edge_jump"),
                        fmt::format("must be in (0, 1] (a step as a share of the depth), got {}", edge_jump));
    core::requireInRange(edge_margin_px, "edge_margin_px", 0, 100);
    core::requireOption(scale >= 0.05 && scale <= 1, option(scale, "scale"),
                        fmt::format("must be in [0.05, 1] (a twentieth of the image at least), got {}", scale));
    core::requireInRange(frame_step, "frame_step", 1, 1000);
    core::requireInRange(live_every, "live_every", 0, 1000);
    // A queued frame holds its full images (about 2 MB at 640 x 480): 1024 of them are 2 GB.
    core::requireInRange(queue_frames, "queue_frames", 1, 1024);
    core::requireOption(live_cloud_voxel >= 0.001 && live_cloud_voxel <= 1, option(live_cloud_voxel, "live_cloud_voxel"),
                        fmt::format("must be in [0.001, 1] m, got {}", live_cloud_voxel));
    core::requireOption(live_period_s >= 0.001 && live_period_s <= 3600, option(live_period_s, "live_period_s"),
                        fmt::format("must be in [0.001, 3600] s, got {}", live_period_s));
    core::requireOption(grid_resolution >= 0.001 && grid_resolution <= 1, option(grid_resolution, "grid_resolution"),
                        fmt::format("must be in [0.001, 1] m (a cell smaller than a millimetre maps no obstacle a "
                                    "robot meets), got {}",
                                    grid_resolution));
    core::requireInRange(grid_min_height, "grid_min_height", 0.0, 10.0);
    core::requireInRange(carve_sigmas, "carve_sigmas", 0.0, 20.0);
    core::requireInRange(carve_min_votes, "carve_min_votes", 1, 100000);
    core::requireInRange(carve_recent_votes, "carve_recent_votes", 0, 100000);
    core::requireOption(grid_max_height > grid_min_height && grid_max_height <= 10, option(grid_max_height, "grid_max_height"),
                        fmt::format("must be > grid_min_height ({}) and <= 10 m, got {}", grid_min_height,
                                    grid_max_height),
                        {option(grid_min_height, "grid_min_height")});
  }

  // check(), and the margins against the camera's image: a margin of half the image or more leaves nothing to fuse.
  void checkFor(const core::CameraIntrinsics& camera) const {
    check();
    const int half = std::min(camera.width, camera.height) / 2;
    if (half <= 0) return;  // the image size is not known (it is taken from the first frame)
    core::requireOption(mask_margin_px < half, core::option(mask_margin_px, "mask_margin_px"),
                        fmt::format("must be below half the image ({} px of {} x {}), got {}", half, camera.width,
                                    camera.height, mask_margin_px));
    core::requireOption(edge_margin_px < half, core::option(edge_margin_px, "edge_margin_px"),
                        fmt::format("must be below half the image ({} px of {} x {}), got {}", half, camera.width,
                                    camera.height, edge_margin_px));
  }
};

}  // namespace amos::dense
