#pragma once
// The Dense.* keys: the settings name and meaning of each member of DenseOptions, for a key list that has
// add(name, &member, meaning) (config::KeySection; run/settings_sections.h registers the section). Written against
// that one call so that the dense module, which stands below config, need not include it.
#include "amos/dense/dense_options.h"

namespace amos::dense {

template <typename KeyList>
void listDenseKeys(DenseOptions& o, KeyList& s) {
  s.add("Dense.voxelSize", &o.voxel_size, "edge of a TSDF voxel (m); about 2 sigma of the depth noise at 3 m");
  s.add("Dense.truncation", &o.truncation,
        "half-width of the signed-distance band (m), at least 2 voxels; 3 sigma of the depth noise at maxDepth");
  s.add("Dense.minDepth", &o.min_depth, "depth readings nearer than this are not fused (m)");
  s.add("Dense.maxDepth", &o.max_depth, "depth readings farther than this are not fused (m)");
  s.add("Dense.maskMargin", &o.mask_margin_px,
        "the dynamic mask grows by this many pixels before fusion (its border and a mover's silhouette are left out)");
  s.add("Dense.edgeJump", &o.edge_jump,
        "a depth step above edgeJump x depth within 3x3 pixels is a depth discontinuity, not fused");
  s.add("Dense.edgeMargin", &o.edge_margin_px, "pixels left out around a depth discontinuity");
  s.add("Dense.scale", &o.scale, "depth and colour are fused at this fraction of the image size");
  s.add("Dense.frameStep", &o.frame_step, "every frameStep-th tracked frame is kept and fused");
  s.add("Dense.liveEvery", &o.live_every,
        "the live volume (live view, tracked poses) fuses every liveEvery-th kept frame; the final map is fused "
        "anew from all kept frames with the final trajectory (0 = no live volume)");
  s.add("Dense.queueFrames", &o.queue_frames, "frames waiting for the fusion thread at most (more are dropped)");
  s.add("Dense.liveCloudVoxel", &o.live_cloud_voxel, "the live cloud for the viewer is downsampled to this (m)");
  s.add("Dense.livePeriod", &o.live_period_s, "seconds between two live clouds for the viewer at least");
  s.add("Dense.gridResolution", &o.grid_resolution, "cell size of occupancy.pgm (m)");
  s.add("Dense.gridMinHeight", &o.grid_min_height,
        "surface higher than this above the floor (m) marks a cell occupied ...");
  s.add("Dense.gridMaxHeight", &o.grid_max_height, "... up to this height (m)");
  s.add("Dense.carve", &o.carve,
        "free-space carving in the final fusion: surface that later frames see through is forgotten (0 = off)");
  s.add("Dense.carveSigmas", &o.carve_sigmas,
        "a reading sees through a surface point when it lies beyond it by more than truncation + carveSigmas x the "
        "depth noise at that range");
  s.add("Dense.carveMinVotes", &o.carve_min_votes,
        "frames that must see through a surface point (and more than see it) before it is carved");
  s.add("Dense.carveRecentVotes", &o.carve_recent_votes,
        "... or that saw through it in a row since it was last seen (a person who stood, then left; 0 = off)");
}

}  // namespace amos::dense
