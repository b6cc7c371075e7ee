#pragma once
// Settings of the dense static map (`run --dense`, the Dense.* keys; docs/dense.md says why each default is what it
// is). Header-only so that the config module can parse the keys whether or not the dense module itself is built
// (it needs Open3D: AMOS_WITH_OPEN3D).
//
// The defaults follow the depth sensor's noise. Structured-light sensors (Kinect v1, Xtion: TUM, Bonn) measure depth
// with sigma(z) ~ 1.5 mm + 1.5e-3 * (z - 0.4)^2 m (Nguyen, Izadi, Lovell 2012): 5 mm at 2 m, 12 mm at 3 m, 21 mm at
// 4 m. A voxel of 2 cm is about 2 sigma at 3 m, where most of a room is seen from; the truncation band must hold the
// surface's noise on both sides (3 sigma at the farthest depth fused), 6 cm = 3 sigma at 4 m, so maxDepth = 4 m.
// Beyond it a reading's noise is larger than the band and would blur the surface it lands on.
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

  // Throws core::InvalidOption naming the member at fault.
  void check() const {
    using core::option;
    core::requirePositive(voxel_size, "voxel_size");
    core::requireOption(truncation >= 2 * voxel_size, option(truncation, "truncation"),
                        fmt::format("must be >= 2 x voxel_size ({}), got {}", 2 * voxel_size, truncation),
                        {option(voxel_size, "voxel_size")});
    core::requirePositive(min_depth, "min_depth");
    core::requireOption(max_depth > min_depth, option(max_depth, "max_depth"),
                        fmt::format("must be > min_depth ({}), got {}", min_depth, max_depth),
                        {option(min_depth, "min_depth")});
    core::requireAtLeast(mask_margin_px, "mask_margin_px", 0);
    core::requirePositive(edge_jump, "edge_jump");
    core::requireAtLeast(edge_margin_px, "edge_margin_px", 0);
    core::requireOption(scale > 0 && scale <= 1, option(scale, "scale"), fmt::format("must be in (0, 1], got {}", scale));
    core::requireAtLeast(frame_step, "frame_step", 1);
    core::requireAtLeast(live_every, "live_every", 0);
    core::requireAtLeast(queue_frames, "queue_frames", 1);
    core::requirePositive(live_cloud_voxel, "live_cloud_voxel");
    core::requirePositive(live_period_s, "live_period_s");
    core::requirePositive(grid_resolution, "grid_resolution");
    core::requireAtLeast(grid_min_height, "grid_min_height", 0.0);
    core::requireOption(grid_max_height > grid_min_height, option(grid_max_height, "grid_max_height"),
                        fmt::format("must be > grid_min_height ({}), got {}", grid_min_height, grid_max_height),
                        {option(grid_min_height, "grid_min_height")});
  }
};

}  // namespace amos::dense
