#pragma once
// Between the dense map's plain data (dense_map.h) and Open3D's geometry, which the volume extracts and the
// downsampling takes. Colours: Open3D's doubles in [0, 1] <-> bytes, clamped and rounded as Open3D's own PLY writer
// rounds them.
#include "amos/dense/dense_map.h"

namespace open3d::geometry {
class PointCloud;
class TriangleMesh;
}  // namespace open3d::geometry

namespace amos::dense {

DenseMesh plainMesh(const open3d::geometry::TriangleMesh& mesh);
DenseCloud plainCloud(const open3d::geometry::PointCloud& cloud);
open3d::geometry::PointCloud open3dCloud(const DenseCloud& cloud);

}  // namespace amos::dense
