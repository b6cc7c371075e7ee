#pragma once
// The dense map's files in a run's output folder, in the trajectory's world frame:
//   mesh.ply            coloured triangle mesh (marching cubes of the TSDF), binary PLY, with vertex normals
//   cloud.ply           the surface's points (the TSDF's zero crossings), coloured, binary PLY
//   removed_points.ply  the dynamic readings left out of fusion, back-projected with their frames' final poses and
//                       downsampled to one per voxel, coloured, binary PLY
//   occupancy.pgm/.yaml the floor plan (occupancy_grid.h), when a floor was found
// Each file is written under a temporary name and renamed: a killed run never leaves half a file.
#include <string>
#include <vector>

#include "amos/dense/dense_mapper.h"

namespace amos::dense {

// The names above (the run's manifest).
const std::vector<std::string>& denseOutputNames();

// Throws core::Error naming the file that cannot be written.
void writeDenseOutputs(const std::string& dir, const DenseMap& map);

}  // namespace amos::dense
