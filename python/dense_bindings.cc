#include "dense_bindings.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fmt/format.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "amos/dense_map.h"

namespace amos::python {

namespace py = pybind11;
namespace fs = std::filesystem;

namespace {

// An N x 3 array copied from N contiguous triples (Eigen::Vector3d, std::array<T, 3>) of element type T.
template <typename T, typename Triple>
py::array_t<T> rowsOf(const std::vector<Triple>& triples) {
  static_assert(sizeof(Triple) == 3 * sizeof(T), "a triple is three packed elements");
  py::array_t<T> out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(triples.size()), 3});
  if (!triples.empty()) std::memcpy(out.mutable_data(), triples.data(), triples.size() * sizeof(Triple));
  return out;
}

py::array_t<std::uint8_t> cellsOf(const OccupancyGrid& g) {
  py::array_t<std::uint8_t> out(std::vector<py::ssize_t>{g.rows, g.cols});
  if (!g.cells.empty()) std::memcpy(out.mutable_data(), g.cells.data(), g.cells.size());
  return out;
}

// Writes with the GIL released (a large mesh takes a moment).
template <typename Writer>
auto writer(Writer write) {
  return [write](const DenseMap& map, const fs::path& path) {
    py::gil_scoped_release release;
    write(map, path.string());
  };
}

void bindGeometry(py::module_& m) {
  py::class_<DenseMesh>(m, "Mesh", "A coloured triangle mesh (marching cubes of the TSDF volume), world frame.")
      .def_property_readonly("vertices", [](const DenseMesh& s) { return rowsOf<double>(s.vertices); },
                             "N x 3 float64 vertex positions (metres; a copy).")
      .def_property_readonly("normals", [](const DenseMesh& s) { return rowsOf<double>(s.normals); },
                             "N x 3 float64 unit vertex normals, or 0 x 3 when the mesh has none (a copy).")
      .def_property_readonly("colors", [](const DenseMesh& s) { return rowsOf<std::uint8_t>(s.colours); },
                             "N x 3 uint8 vertex colours, RGB order (a copy).")
      .def_property_readonly("triangles", [](const DenseMesh& s) { return rowsOf<std::uint32_t>(s.triangles); },
                             "M x 3 uint32 vertex indices, counter-clockwise seen from outside (a copy).")
      .def("__repr__", [](const DenseMesh& s) {
        return fmt::format("Mesh(vertices={}, triangles={})", s.vertices.size(), s.triangles.size());
      }, "A one-line summary.");

  py::class_<DenseCloud>(m, "Cloud", "Coloured points, world frame.")
      .def_property_readonly("points", [](const DenseCloud& s) { return rowsOf<double>(s.points); },
                             "N x 3 float64 positions (metres; a copy).")
      .def_property_readonly("normals", [](const DenseCloud& s) { return rowsOf<double>(s.normals); },
                             "N x 3 float64 unit normals, or 0 x 3 when the cloud has none (a copy).")
      .def_property_readonly("colors", [](const DenseCloud& s) { return rowsOf<std::uint8_t>(s.colours); },
                             "N x 3 uint8 colours, RGB order (a copy).")
      .def("__repr__", [](const DenseCloud& s) { return fmt::format("Cloud(points={})", s.points.size()); },
           "A one-line summary.");

  py::class_<OccupancyGrid>(m, "OccupancyGrid", R"(The floor plan: a 2D occupancy grid, ROS map_server meaning.

cells: 254 free, 0 occupied, 205 unknown; row 0 is the top (the largest map y), as in the PGM.)")
      .def_property_readonly("cells", &cellsOf, "rows x cols uint8 array of cells (a copy).")
      .def_property_readonly("origin", [](const OccupancyGrid& g) { return py::make_tuple(g.origin.x(), g.origin.y()); },
                             "(x, y) in the map frame of the lower-left cell's corner (metres).")
      .def_readonly("resolution", &OccupancyGrid::resolution, "Metres per cell.")
      .def_property_readonly("T_mw", [](const OccupancyGrid& g) { return Eigen::Matrix4d(g.T_mw); },
                             "4 x 4 float64, world -> map frame (on the floor, z up).")
      .def_property_readonly("floor_normal", [](const OccupancyGrid& g) { return Eigen::Vector3d(g.floor_normal); },
                             "The floor's unit normal in the world (normal . p + offset = 0).")
      .def_readonly("floor_offset", &OccupancyGrid::floor_offset, "The floor plane's offset.")
      .def("__repr__", [](const OccupancyGrid& g) {
        return fmt::format("OccupancyGrid(rows={}, cols={}, resolution={}, origin=({:.3f}, {:.3f}))", g.rows, g.cols,
                           g.resolution, g.origin.x(), g.origin.y());
      }, "A one-line summary.");
}

void bindMaps(py::module_& m) {
  py::class_<DenseMap>(m, "DenseMap", R"(The dense static map (Slam.dense_map()), fused with the final trajectory.

    m = slam.dense_map()
    m.write_mesh_ply("mesh.ply")
    if m.grid is not None:
        m.write_floor_plan("occupancy")    # occupancy.pgm + occupancy.yaml)")
      .def_readonly("mesh", &DenseMap::mesh, "The Mesh.")
      .def_readonly("cloud", &DenseMap::cloud, "The surface's points (Cloud: the TSDF's zero crossings).")
      .def_readonly("removed", &DenseMap::removed, "The dynamic readings left out of fusion (Cloud, one per voxel).")
      .def_readonly("grid", &DenseMap::grid, "The floor plan (OccupancyGrid), or None when no floor was found.")
      .def_readonly("frames_fused", &DenseMap::frames_fused, "Frames fused into the map.")
      .def("write_mesh_ply", writer(&writeMeshPly), py::arg("path"),
           "Writes the mesh as a binary PLY (as `amos-slam run --dense` writes mesh.ply).")
      .def("write_cloud_ply", writer(&writeCloudPly), py::arg("path"),
           "Writes the surface cloud as a binary PLY (as cloud.ply).")
      .def("write_floor_plan", writer(&writeFloorPlan), py::arg("stem"),
           "Writes the floor plan as <stem>.pgm + <stem>.yaml (ROS map_server); an error when grid is None.")
      .def("__repr__", [](const DenseMap& d) {
        return fmt::format("DenseMap(mesh_vertices={}, cloud_points={}, grid={}, frames_fused={})",
                           d.mesh.vertices.size(), d.cloud.points.size(),
                           d.grid ? fmt::format("{}x{}", d.grid->cols, d.grid->rows) : "None", d.frames_fused);
      }, "A one-line summary.");

  py::class_<DenseSnapshot>(m, "DenseSnapshot",
                            "The live volume's surface while running (Slam.dense_snapshot()), tracking poses.")
      .def_readonly("cloud", &DenseSnapshot::cloud, "The surface's points, downsampled (Cloud).")
      .def_readonly("frames_fused", &DenseSnapshot::frames_fused, "Frames fused into the live volume so far.")
      .def("__repr__", [](const DenseSnapshot& s) {
        return fmt::format("DenseSnapshot(points={}, frames_fused={})", s.cloud.points.size(), s.frames_fused);
      }, "A one-line summary.");

  m.attr("dense_available") = denseMappingAvailable();
}

}  // namespace

void bindDense(py::module_& m) {
  bindGeometry(m);
  bindMaps(m);
}

}  // namespace amos::python
