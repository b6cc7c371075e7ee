#pragma once
// The dense products as the page receives them (`/api/dense/NAME.bin`): one binary block per layer, read by the
// page straight into typed arrays (no JSON for hundreds of thousands of points). Little-endian:
//   uint32 vertex count V, uint32 triangle count T,
//   float32 x y z  x V,  uint32 i j k  x T,  uint8 r g b  x V
// (every part starts at a multiple of 4 bytes). A point cloud has T = 0.
#include <cstddef>
#include <string>

#include "amos/viewer/ply_file.h"

namespace amos::viewer {

// Throws core::Error when the sizes do not match (xyz and rgb of 3 per vertex, 3 indices per triangle).
std::string encodeDenseLayer(const ColouredGeometry& geometry);

// At most `max_points` of a point cloud (every k-th point, in order): the live view of a dense cloud stays light
// for the browser whatever its size. Triangles are not kept (a mesh is never thinned this way).
ColouredGeometry thinPoints(ColouredGeometry cloud, std::size_t max_points);

}  // namespace amos::viewer
